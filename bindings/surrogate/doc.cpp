// SPDX-License-Identifier: MIT
// Reference texts of smi.doe, smi.kriging, smi.propagate and smi.screen (this folder). Defaults
// are read from the kernels' option structs (surrogate/doe.hpp, kriging.hpp, screen.hpp,
// screen_surrogate.hpp, sequential_design.hpp) and core/defaults.hpp.
#include "bindings/doc.hpp"
#include "bindings/surrogate/doe_options.hpp"
#include "bindings/surrogate/kriging_options.hpp"
#include "bindings/surrogate/propagate_options.hpp"
#include "bindings/surrogate/screen_options.hpp"
#include "bindings/surrogate/sequential_options.hpp"
#include "kernels/surrogate/doe.hpp"
#include "kernels/surrogate/kriging.hpp"
#include "kernels/surrogate/poly_ridge.hpp"
#include "kernels/surrogate/screen.hpp"
#include "kernels/surrogate/screen_surrogate.hpp"
#include "kernels/surrogate/sequential_design.hpp"
#include "platform/core/defaults.hpp"

namespace smi::bind {
namespace {

const char* const kSurrogateText = R"DOC(
@ module smi.doe
Designs of experiments as matrices (rows = points): optimized Latin hypercubes, Sobol sequences,
full factorials. space is a dimension count (the unit cube) or one entry per input: {lo, hi}
(scaled to the bounds) or a dist (pushed through its quantile function).

@ smi.doe.lhs(n, space [, opts]) -> mat
An optimized Latin hypercube of n points (ESE optimisation of maximin or phi_p), the same design
for the same seed.
options:
${lhs_options}
returns: an n x d mat
errors: n not an integer in 1..2^28; a bad space entry (named by index, e.g. "space[2] = {1, 0}
  needs finite lo < hi"); an unknown criterion or option
example:
  local X = smi.doe.lhs(5, {{0, 10}, smi.dist.normal{mean = 0, std = 1}}, {seed = 1})
  print(X:shape())

@ smi.doe.sobol(n, space [, opts]) -> mat
The first n points of the Sobol sequence (Joe-Kuo directions, up to smi.doe.sobol_max_dim inputs).
options:
${sobol_options}
returns: an n x d mat
errors: n out of range; more inputs than smi.doe.sobol_max_dim; a bad space entry
example:
  print(smi.doe.sobol(4, 2))

@ smi.doe.full_factorial(levels | k, space) -> mat
Every combination of levels: full_factorial{{1, 2}, {10, 20, 30}} (one list per input) or
full_factorial(k, space) with k evenly spaced levels per input of space (cell midpoints for a
dist).
returns: a mat with one row per combination (the first input varies slowest)
errors: k < 2; a level list that is not numbers
example:
  print(smi.doe.full_factorial{{1, 2}, {10, 20}})

@ module smi.kriging
Universal Kriging (DACE-compatible): smi.kriging.fit and smi.kriging.load give a model with the
methods smi.kriging:predict, :loo, :evaluate, :save.

@ smi.kriging.fit(X, y [, opts]) -> model
Fits a Kriging model to the points X (rows) and responses y: regression trend plus a Gaussian
process, theta by maximum likelihood on the analytic gradient with a seeded multistart and
data-scaled bounds, or DACE's boxmin.
options:
${kriging_fit_options}
returns: a model (smi.kriging) with fields theta, beta, sigma2, n, trend, corr, method, nugget,
  inputs, output, warnings, evaluations
errors: X and y of different lengths; fewer points than trend terms; two identical points; an
  unknown trend, corr or option; inputs of the wrong count
example:
  local X = smi.doe.lhs(12, {{0, 1}, {0, 1}}, {seed = 1})
  local y = smi.vec(12)
  for i = 1, 12 do y[i] = math.sin(3 * X:get(i, 1)) + X:get(i, 2) end
  local k = smi.kriging.fit(X, y, {inputs = {"a", "b"}})
  print(k.n, k:predict(smi.mat{{0.5, 0.5}}))

@ smi.kriging.load(path) -> model
Loads a model written by model:save (names of inputs and output included).
returns: a model (smi.kriging)
errors: the sandbox refuses the path; not a model file, or a newer format version
example:
  local k = smi.kriging.fit(smi.mat{{0}, {0.5}, {1}}, smi.vec{0, 1, 0}, {theta = 1})
  k:save(smi.out("doc_k.model"))
  print(smi.kriging.load(smi.out("doc_k.model")).n)

@ smi.kriging.sequential{model =, design =, candidates =} -> {X =, Y =, kriging =, history =, reached =, stop =}
A sequential Kriging design: the model runs on `design`, a Kriging is fitted per output, and
while an output misses its leave-one-out target a batch of candidate rows is added, each the
candidate with the largest weight x Kriging variance given the design and the batch so far (the
variance needs no response, so the whole batch goes to the model, and a parallel evaluator, in
one call). Weights say where the input distributions put their mass.
options:
${sequential_options}
returns: the design X, the outputs Y {output = vec}, the last Kriging per output, the history
  ({points, q2 = {output = x}, rmse = {...}} per round), reached (the targets were met) and stop
  (why it stopped)
errors: sizes that do not match; weights not finite or none positive; max below the design's size
example:
  local f = function(X) return {y = (X:col(1) * 6):map(math.sin)} end
  local r = smi.kriging.sequential{model = f, design = smi.doe.lhs(5, {{0, 1}}, {seed = 1}),
    candidates = smi.doe.lhs(200, {{0, 1}}, {seed = 2}), batch = 3, max = 30, q2 = 0.9999}
  print(r.reached, r.X:rows() <= 30)

@ smi.kriging:predict(X [, opts]) -> mean, mse
Predictions at the rows of X, on both cores for large X.
options:
${kriging_predict_options}
returns: a vec of means and (with mse) a vec of MSEs
errors: X with a different number of columns than the model's inputs
example:
  local k = smi.kriging.fit(smi.mat{{0}, {0.5}, {1}}, smi.vec{0, 1, 0}, {theta = 1})
  print(k:predict(smi.mat{{0.25}}))

@ smi.kriging:loo() -> {residuals =, variance =, q2 =, rmse =}
Closed-form leave-one-out cross-validation (no refit): residuals y_i - yhat_(-i), their variances,
Q2 = 1 - PRESS / total sum of squares, and the RMSE.
returns: a table of vecs and numbers
errors: none
example:
  local X = smi.doe.lhs(10, 1, {seed = 2})
  local k = smi.kriging.fit(X, X:col(1):map(math.sin))
  print(k:loo().q2 > 0.9)

@ smi.kriging:evaluate(X) -> {output = vec}
The model's mean as a named model (the form smi.propagate and smi.calibrate call).
returns: a table {<output name> = vec}
errors: X with the wrong number of columns
example:
  local k = smi.kriging.fit(smi.mat{{0}, {1}}, smi.vec{1, 3}, {theta = 1, output = "f"})
  print(k:evaluate(smi.mat{{0}}).f)

@ smi.kriging:save(path)
Writes the model (text, version 2, with input and output names) for smi.kriging.load.
returns: nothing
errors: the sandbox refuses the path (smi.out(name) is always allowed); the file cannot be written
example:
  local k = smi.kriging.fit(smi.mat{{0}, {1}}, smi.vec{1, 3}, {theta = 1})
  k:save(smi.out("doc_save.model"))
  print("saved")

@ smi.propagate{model =, inputs =} -> outputs, X
Monte Carlo propagation: n points drawn from the inputs pushed through the model on whole
matrices. The draws are common random numbers: the same seed gives the same points for any
model, so two models (or two calibration steps) are compared without sampling noise.
options:
${propagate_options}
returns: outputs {name = vec} and the input matrix X (rows = points)
errors: a missing model or inputs; an input the model does not know, or one it needs missing
  (named); the model returning the wrong number of rows
example:
  local Y = smi.propagate{model = function(X) return {y = X:col(1) * 2} end,
                          inputs = {{"a", smi.dist.normal{mean = 1, std = 0.1}}}, n = 1000, seed = 1}
  print(("mean %.3f, std %.3f"):format(Y.y:mean(), Y.y:std()))

@ smi.screen{model =, inputs =} -> ranking
Variance-based screening: the PDF-area index of each input (paper eq. 3 and 7: the area between
the output's PDF with the input varying and with it fixed), beside Sobol first-order and total
indices with bootstrap intervals.
options:
${screen_options}
returns: rows {input, e, ne, rank, s1, s1_lo, s1_hi, st, st_lo, st_hi} sorted by rank, with fields
  output, n, variance, warnings, by_input; tostring() prints the table. Several outputs and no
  `output`: a table of rankings by output name
errors: as smi.propagate; an output the model does not have
example:
  local r = smi.screen{model = function(X) return {y = X:col(1) * 3 + X:col(2)} end,
                       inputs = {{"a", smi.dist.uniform{lower = 0, upper = 1}}, {"b", smi.dist.uniform{lower = 0, upper = 1}}},
                       n = 2000, seed = 1, bootstrap = 0}
  print(r[1].input, r[1].rank)
)DOC";

}  // namespace

DocText doc_surrogate() {
  return {"bindings/surrogate/doc.cpp",
          fill(kSurrogateText, {{"lhs_options", surrogate::lhs_schema().doc()},
                       {"screen_options", surrogate::screen_schema().doc()},
                       {"kriging_fit_options", surrogate::kriging_fit_schema().doc()},
                       {"kriging_predict_options", surrogate::kriging_predict_schema().doc()},
                       {"sobol_options", surrogate::sobol_schema().doc()},
                       {"propagate_options", surrogate::propagate_schema().doc()},
                       {"sequential_options", surrogate::sequential_schema().doc()}})};
}

}  // namespace smi::bind
