// SPDX-License-Identifier: MIT
#pragma once
// The option schemas of the distribution constructors smi.dist.<family>{...}
// (luax/option_schema.hpp): dist_lua.cpp reads each family's table with its schema, dist_doc.cpp
// lists the options from them. A parameter not given is NaN; which ones a family needs (and
// which pairs are alternatives: lognormal's mean/std or mu_log/sigma_log, gamma's scale or rate)
// is dist_lua.cpp's. The defaults below are the families' own (a shift of 0, beta on [0, 1]).
#include <limits>

#include "luax/option_schema.hpp"

namespace smi::bind::stats {

inline constexpr double kNotGiven = std::numeric_limits<double>::quiet_NaN();

struct NormalArgs {
  double mean = kNotGiven, std = kNotGiven;
};
struct LognormalArgs {
  double mean = kNotGiven, std = kNotGiven, mu_log = kNotGiven, sigma_log = kNotGiven;
};
struct UniformArgs {
  double lower = kNotGiven, upper = kNotGiven, mean = kNotGiven, std = kNotGiven;
};
struct TruncnormalArgs {
  double mean = kNotGiven, std = kNotGiven;
  double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
};
struct WeibullArgs {
  double shape = kNotGiven, scale = kNotGiven, loc = 0.0;
};
struct GumbelArgs {
  double loc = kNotGiven, scale = kNotGiven;
};
struct GammaArgs {
  double shape = kNotGiven, scale = kNotGiven, rate = kNotGiven, loc = 0.0;
};
struct BetaArgs {
  double alpha = kNotGiven, beta = kNotGiven, lower = 0.0, upper = 1.0;
};
struct TriangularArgs {
  double lower = kNotGiven, mode = kNotGiven, upper = kNotGiven;
};

const lua::Schema<NormalArgs>& normal_schema();
const lua::Schema<LognormalArgs>& lognormal_schema();
const lua::Schema<UniformArgs>& uniform_schema();
const lua::Schema<TruncnormalArgs>& truncnormal_schema();
const lua::Schema<WeibullArgs>& weibull_schema();
const lua::Schema<GumbelArgs>& gumbel_schema();
const lua::Schema<GammaArgs>& gamma_schema();
const lua::Schema<BetaArgs>& beta_schema();
const lua::Schema<TriangularArgs>& triangular_schema();

}  // namespace smi::bind::stats
