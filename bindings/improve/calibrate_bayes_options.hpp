// SPDX-License-Identifier: MIT
#pragma once
// The option schemas of smi.calibrate_bayes (luax/option_schema.hpp): the scalar options go into
// BayesSpec (the kernels' TmcmcOptions and PopulationOptions hold their defaults); the forms'
// tables are by_hand entries read by calibrate_bayes_spec.cpp. doc.cpp takes the reference's
// option list from it.
#include <limits>
#include <string>

#include "bindings/improve/calibrate_bayes_spec.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::improve {

const lua::Schema<BayesSpec>& calibrate_bayes_schema();

/// A prior table: {dist =, mean =, std =, lower =, upper =} (objective form: parameters[i].prior)
/// or {param =, dist =, mean =, std =} (model form: prior[i]). NaN: not given.
struct BayesPriorArgs {
  std::string param;
  std::string dist = "normal";
  double mean = std::numeric_limits<double>::quiet_NaN();
  double std = std::numeric_limits<double>::quiet_NaN();
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};
/// Read with the entry's name ("prior[2]", "parameters[1].prior") in its messages.
const lua::Schema<BayesPriorArgs>& bayes_prior_schema();

}  // namespace smi::bind::improve
