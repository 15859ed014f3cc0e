// SPDX-License-Identifier: MIT
// The option schemas of the distribution constructors (dist_options.hpp), in the reference's order.
#include "bindings/stats/dist_options.hpp"

#include <vector>

namespace smi::bind::stats {

using namespace smi::lua;

namespace {

/// A parameter: "(required)", "nil" (one of a pair of alternatives) or "" (the struct's default).
template <class S>
Option<S> param(const char* key, double S::*m, const char* doc, const char* shown = "(required)") {
  return number<S>(key, m, any_value(), doc, shown);
}
constexpr const char* kNil = "nil";
constexpr const char* kDefault = "";

}  // namespace

const Schema<NormalArgs>& normal_schema() {
  using S = NormalArgs;
  static const Schema<S> s("smi.dist.normal", std::vector<Option<S>>{param<S>("mean", &S::mean, "the mean"),
                                                                      param<S>("std", &S::std, "the standard deviation, > 0")});
  return s;
}

const Schema<LognormalArgs>& lognormal_schema() {
  using S = LognormalArgs;
  static const Schema<S> s("smi.dist.lognormal", std::vector<Option<S>>{
      param<S>("mean", &S::mean, "the mean of the variable (with std)", kNil),
      param<S>("std", &S::std, "the standard deviation of the variable", kNil),
      param<S>("mu_log", &S::mu_log, "the mean of log(X) (with sigma_log, instead of mean/std)", kNil),
      param<S>("sigma_log", &S::sigma_log, "the standard deviation of log(X)", kNil)});
  return s;
}

const Schema<UniformArgs>& uniform_schema() {
  using S = UniformArgs;
  static const Schema<S> s("smi.dist.uniform", std::vector<Option<S>>{
      param<S>("lower", &S::lower, "the lower end (with upper)", kNil), param<S>("upper", &S::upper, "the upper end", kNil),
      param<S>("mean", &S::mean, "the mean (with std, instead of lower/upper)", kNil),
      param<S>("std", &S::std, "the standard deviation: the width is std * sqrt(12)", kNil)});
  return s;
}

const Schema<TruncnormalArgs>& truncnormal_schema() {
  using S = TruncnormalArgs;
  static const Schema<S> s("smi.dist.truncnormal", std::vector<Option<S>>{
      param<S>("mean", &S::mean, "the parent's mean"), param<S>("std", &S::std, "the parent's standard deviation"),
      param<S>("lower", &S::lower, "the lower truncation point", kDefault),
      param<S>("upper", &S::upper, "the upper truncation point", kDefault)});
  return s;
}

const Schema<WeibullArgs>& weibull_schema() {
  using S = WeibullArgs;
  static const Schema<S> s("smi.dist.weibull", std::vector<Option<S>>{param<S>("shape", &S::shape, "k > 0"),
                                                                       param<S>("scale", &S::scale, "lambda > 0"),
                                                                       param<S>("loc", &S::loc, "a shift", kDefault)});
  return s;
}

const Schema<GumbelArgs>& gumbel_schema() {
  using S = GumbelArgs;
  static const Schema<S> s("smi.dist.gumbel", std::vector<Option<S>>{param<S>("loc", &S::loc, "the mode"),
                                                                      param<S>("scale", &S::scale, "beta > 0")});
  return s;
}

const Schema<GammaArgs>& gamma_schema() {
  using S = GammaArgs;
  static const Schema<S> s("smi.dist.gamma", std::vector<Option<S>>{
      param<S>("shape", &S::shape, "k > 0"), param<S>("scale", &S::scale, "theta > 0 (or give rate)", kNil),
      param<S>("rate", &S::rate, "1/theta", kNil), param<S>("loc", &S::loc, "a shift", kDefault)});
  return s;
}

const Schema<BetaArgs>& beta_schema() {
  using S = BetaArgs;
  static const Schema<S> s("smi.dist.beta", std::vector<Option<S>>{
      param<S>("alpha", &S::alpha, "> 0"), param<S>("beta", &S::beta, "> 0"),
      param<S>("lower", &S::lower, "the lower end", kDefault), param<S>("upper", &S::upper, "the upper end", kDefault)});
  return s;
}

const Schema<TriangularArgs>& triangular_schema() {
  using S = TriangularArgs;
  static const Schema<S> s("smi.dist.triangular", std::vector<Option<S>>{
      param<S>("lower", &S::lower, "the lower end"), param<S>("mode", &S::mode, "the peak, in [lower, upper]"),
      param<S>("upper", &S::upper, "the upper end")});
  return s;
}

}  // namespace smi::bind::stats
