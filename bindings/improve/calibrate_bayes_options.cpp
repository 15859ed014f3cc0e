// SPDX-License-Identifier: MIT
// The option schemas of smi.calibrate_bayes (calibrate_bayes_options.hpp), in the reference's order.
#include "bindings/improve/calibrate_bayes_options.hpp"

#include <vector>

#include "kernels/improve/crn_mapping.hpp"

namespace smi::bind::improve {

using namespace smi::lua;
using smi::improve::CrnKind;

// long: one table of entries, one per option in the reference's order (data, no logic)
const Schema<BayesSpec>& calibrate_bayes_schema() {
  using S = BayesSpec;
  static const Schema<S> schema("smi.calibrate_bayes", std::vector<Option<S>>{
      by_hand<S>("parameters", "nil",
         "objective form: {{name =, lower =, upper =} (uniform prior) | {name =,\n"
         "prior = {dist = \"normal\"|\"lognormal\", mean =, std =, lower =, upper =}}, ...}"),
      by_hand<S>("loglik", "nil",
         "objective form: function(Theta) -> vec of log-likelihoods, one per row of\n"
         "the smi.mat Theta (called once per batch of points)"),
      by_hand<S>("model", "nil",
         "model form: as smi.calibrate's (a function(X), an smi.model, an smi.kriging\n"
         "or {response = kriging})"),
      by_hand<S>("inputs", "nil",
         "model form: as smi.calibrate's; ranges {lo, hi, start} are the calibrated\n"
         "parameters (\"x.mean\", \"x.std\") and their default uniform priors"),
      by_hand<S>("data", "nil",
         "model form: {response = vec}, one entry per specimen, the same order in\n"
         "every response (a specimen's responses are taken jointly)"),
      by_hand<S>("noise", "nil",
         "model form: {response = sd} measurement noise; a response without one gets\n"
         "noise_fraction times its data's standard deviation"),
      by_hand<S>("prior", "nil",
         "model form: {{param = \"x.mean\", dist = \"normal\"|\"lognormal\", mean =, std =},\n"
         "...}: a density on that parameter, truncated to its range; the others\n"
         "are uniform on their ranges"),
      by_hand<S>("order", "nil",
         "model form: the input column order for a function model (names)"),
      integer<S>("samples", [](auto& s) -> auto& { return s.sampler.samples; }, at_least(smi::improve::kMinParticles),
         "particles of the sampler (and posterior samples returned)"),
      integer<S>("max_stages", [](auto& s) -> auto& { return s.sampler.max_stages; }, at_least(1),
         "tempering stages at most (not converged when beta has not reached 1)"),
      integer<S>("seed", [](auto& s) -> auto& { return s.sampler.seed; }, any_value(),
         "seed of the sampler and of the common random numbers", "smi.seed"),
      number<S>("target_cov", [](auto& s) -> auto& { return s.sampler.target_cov; }, above(0),
         "coefficient of variation of the stage weights that sets each beta step"),
      integer<S>("min_sweeps", [](auto& s) -> auto& { return s.sampler.min_sweeps; }, at_least(1),
         "Metropolis sweeps of all chains per stage, at least"),
      integer<S>("max_sweeps", [](auto& s) -> auto& { return s.sampler.max_sweeps; }, at_least(1),
         "and at most"),
      number<S>("moves", [](auto& s) -> auto& { return s.sampler.moves; }, at_least(0),
         "sweeps run until each chain has moved about this often (accepted steps)"),
      number<S>("target_correlation", [](auto& s) -> auto& { return s.sampler.target_correlation; }, above(0),
         "and until the chains' end points keep at most this correlation with their\n"
         "seeds (they have forgotten where they started)"),
      integer<S>("n", [](auto& s) -> auto& { return s.population.n; }, at_least(2),
         "model form: propagated samples per parameter point (common random numbers)"),
      choice<S>("crn", [](auto& s) -> auto& { return s.population.crn; }, Names<CrnKind>{{"random", CrnKind::random}, {"quantiles", CrnKind::quantiles}},
         "model form: \"random\" or \"quantiles\" (stratified) common random numbers"),
      number<S>("bandwidth", [](auto& s) -> auto& { return s.population.bandwidth; }, at_least(0),
         "model form: factor on the normal-reference bandwidth of the response-space\n"
         "kernel (0: the noise kernel alone, unbiased but noisier)"),
      number<S>("noise_fraction", &S::noise_fraction, above(0),
         "model form: default noise sd as a fraction of each response's data sd"),
      integer<S>("threads", [](auto& s) -> auto& { return s.population.threads; }, at_least(1),
         "model form: threads for the input mapping and the kernel sums"),
  });
  (void)bayes_prior_schema();
  return schema;
}

const Schema<BayesPriorArgs>& bayes_prior_schema() {
  using S = BayesPriorArgs;
  static const Schema<S> schema("smi.calibrate_bayes prior", std::vector<Option<S>>{
      string<S>("param", &S::param, {}, "model form: the calibrated parameter", "nil"),
      string<S>("dist", &S::dist, {"normal", "lognormal"}, "the prior's family"),
      number<S>("mean", &S::mean, finite(), "the prior's mean (of the parameter itself)", "(required)"),
      number<S>("std", &S::std, finite_above(0), "its standard deviation, > 0", "(required)"),
      number<S>("lower", &S::lower, any_value(), "objective form: truncated below (the model form's range)"),
      number<S>("upper", &S::upper, any_value(), "objective form: truncated above (the model form's range)"),
  });
  return schema;
}

}  // namespace smi::bind::improve
