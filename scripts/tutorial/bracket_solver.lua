-- SPDX-License-Identifier: MIT
-- Tutorial, steps 2 and 3 (docs/tutorial.md): the same calibration through a command-line
-- solver (smi-beam-solver, built in the tree) with a deck template and an output parser, a Kriging
-- surrogate of the solver, and a report.
--   build/smi-lua --allow-exec build/smi-beam-solver scripts/tutorial/bracket_solver.lua [--points N]
local options = require "smi.options"
local report = require "smi.report"


local opt = options.parse(arg, {
  name = "bracket_solver",
  summary = "calibrates the bracket's modulus through smi-beam-solver and writes a report",
  usage = "smi-lua --allow-exec SOLVER {script} [--solver SOLVER] [options]",
  { name = "solver", type = "path", meaning = "the beam solver program, also given to --allow-exec (default: the"
    .. " first of build/smi-beam-solver and smi-beam-solver on PATH that is allowed)" },
  { name = "points", type = "integer", default = 20, min = 5, meaning = "solver runs in the design of the surrogate" },
  { name = "metric", type = "string", default = "pr", allowed = { "pr", "loglik" }, meaning = "the calibration metric" },
})

local measured = smi.csv.read(smi.script_dir .. "/bracket_tests.csv").freq_hz

-- 1. The solver as a model: a deck per point from the template, the program run in its own
-- folder, the result read back by a parser. Every run is kept in an evaluation store.
-- The solver is looked for where the source tree builds it and on PATH (an installed package),
-- unless --solver names it; a program must also be allowed with --allow-exec.
local function beam_model(program)
  return smi.model.command{
    name = "beam", inputs = {"E", "h"}, outputs = {"freq_hz"},
    template = smi.script_dir .. "/beam.tpl", constants = {b = 20, L = 100}, deck = "beam.deck",
    command = {program, "{deck}"},
    parse = function(dir, h) return {freq_hz = h.regex("beam.out", "freq_hz = (\\S+)")} end,
  }
end
local tried, solver = {}, nil
for _, program in ipairs(opt.solver and {opt.solver} or {"build/smi-beam-solver", "smi-beam-solver"}) do
  local ok, m = pcall(beam_model, program)
  if ok then solver = m break end
  tried[#tried + 1] = ("  %s: %s"):format(program, tostring(m):gsub("^.-smi%.model%.command: ", ""))
end
if not solver then
  smi.fail(("no beam solver found; tried:\n%s\nGive its path to both options: smi-lua --allow-exec PATH %s --solver PATH"):format(
    table.concat(tried, "\n"), arg[0]))
end

-- 2. A design over the inputs' plausible range, run once through the solver.
local X = smi.doe.lhs(opt.points, {{120000, 280000}, {1.85, 2.15}}, {seed = 1})
local Y, info = solver:evaluate(X)
print(("solver: %d points, %d runs launched, %d reused from the store, %d failed"):format(
  X:rows(), info.launched, math.floor(info.reused:sum()), info.failed))

-- 3. A Kriging surrogate of the solver, checked by leave-one-out.
local k = smi.kriging.fit(X, Y.freq_hz, {inputs = {"E", "h"}, output = "freq_hz"})
local loo = k:loo()
print(("kriging: Q2 = %.6f, LOO RMSE = %.2e Hz"):format(loo.q2, loo.rmse))

-- 4. Calibration on the surrogate (thousands of evaluations cost microseconds, not solver runs).
local h_dist = smi.dist.normal{mean = 2.0, std = 0.03}
local r = smi.calibrate{
  model = k, metric = opt.metric,
  inputs = {{name = "E", dist = "normal", mean = {150000, 250000, 180000}, std = {1000, 20000, 5000}},
            {name = "h", dist = "normal", mean = 2.0, std = 0.03}},
  data = {freq_hz = measured},
  design_bounds = {E = {120000, 280000}, h = {1.85, 2.15}},
}
print(("E: mean = %.0f MPa, std = %.0f MPa (%s = %.4f, converged: %s)"):format(
  r.params["E.mean"], r.params["E.std"], opt.metric, r.objective, tostring(r.converged)))

-- 5. Validation with the solver itself at 200 calibrated points, not only the surrogate.
local P = smi.propagate{model = solver, inputs = {{"E", r.distributions.E}, {"h", h_dist}}, n = 200, seed = 7}
local v = smi.metric.upool{data = measured, predicted = smi.kde(P.freq_hz)}
print(v)

-- 6. The report: one self-contained HTML file.
local rep = report.new{title = "Bracket calibration", subtitle = "Tutorial: smi-beam-solver, Kriging, smi.calibrate"}
rep:section("Data")
rep:text(("%d brackets tested; first bending frequency %.2f Hz on average (std %.2f Hz)."):format(#measured, measured:mean(), measured:std()))
rep:section("Calibration")
rep:table{caption = "Calibrated modulus (normal distribution)", columns = {"Parameter", {title = "Value (MPa)", digits = 5}},
          rows = {{"E mean", r.params["E.mean"]}, {"E std", r.params["E.std"]}}}
rep:table{caption = "Surrogate", columns = {"Solver runs", "Q2 (LOO)", "RMSE (Hz)"}, rows = {{X:rows(), loo.q2, loo.rmse}}}
rep:section("Validation")
local chart = report.svg.chart{title = "Measured vs predicted", xlabel = "first bending frequency (Hz)", ylabel = "CDF"}
local pred = smi.kde(P.freq_hz):curve(201)
chart:line(pred.x, pred.cdf, {label = "predicted (200 solver runs)"})
chart:ecdf(measured, {label = "measured"})
rep:figure(chart, "CDF of the predicted frequency and the measured ECDF.")
rep:verdict{name = "u-pooling validation", pass = v.pass, detail = tostring(v), value = v.metric, threshold = v.threshold}
rep:provenance{smi_lua = smi.version, seed = smi.seed, solver = opt.solver, solver_version = solver.version,
               data = "bracket_tests.csv", design_points = X:rows()}
rep:write(smi.out("report.html"))
print("report: " .. smi.out_dir .. "/report.html")
