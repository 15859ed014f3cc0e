// SPDX-License-Identifier: MIT
#pragma once
// Reading the table given to smi.calibrate_bayes{...}: the priors, the sampler's and the
// population likelihood's options, and either the objective form (parameters, loglik) or the
// model form (model, inputs, data, noise, read as smi.calibrate reads them). Runs inside
// protect() before any sampling; errors name the field and the fix. Lua values called back
// stay on the stack at recorded slots.
#include <lua.hpp>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bindings/improve/calibrate_spec.hpp"
#include "kernels/improve/bayes_prior.hpp"
#include "kernels/improve/population_likelihood.hpp"
#include "kernels/improve/tmcmc.hpp"

namespace smi::bind::improve {

/// The table as read. The kernels' option structs hold every default.
struct BayesSpec {
  smi::improve::TmcmcOptions sampler;
  smi::improve::PopulationOptions population;
  /// Default noise sd of a response: this fraction of the data's standard deviation.
  double noise_fraction = 0.05;
  std::vector<smi::improve::Prior> priors;  ///< one per parameter, in r.names order
  bool model_form = false;
  int loglik_slot = 0;  ///< objective form: loglik(Theta)
  // Model form.
  CalibrateSpec population_spec;         ///< model parts, inputs, params, responses (as smi.calibrate reads them)
  std::vector<std::string> responses;    ///< data's response names (sorted)
  Eigen::MatrixXd data;                  ///< specimens x responses
  Eigen::VectorXd noise_sd;              ///< per response
  std::vector<bool> noise_given;         ///< per response: from noise = {...} (else the default)
};

/// Reads the spec table at `idx`; pushes the callback values.
BayesSpec read_bayes_spec(lua_State* L, int idx);

}  // namespace smi::bind::improve
