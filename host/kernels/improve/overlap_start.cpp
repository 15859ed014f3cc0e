#include "kernels/improve/overlap_start.hpp"

#include <fmt/format.h>

#include <cmath>

#include "kernels/core/descriptive.hpp"

namespace smi::improve {

double moment_mismatch(const StatisticalObjective& obj, const Eigen::VectorXd& theta) {
  const Eigen::MatrixXd Y = obj.predict(theta);
  double s = 0.0;
  for (Eigen::Index j = 0; j < Y.cols(); ++j) {
    const ResponseSpec& r = obj.responses()[static_cast<std::size_t>(j)];
    auto [m, sd] = r.moments();
    if (!(sd > 0.0) || !std::isfinite(sd) || !std::isfinite(m)) continue;
    const double pm = Y.col(j).mean(), ps = std::max(stddev(Y.col(j)), 1e-12 * sd);
    s += std::pow((pm - m) / sd, 2) + std::pow(std::log(ps / sd), 2);
  }
  return s;
}

PreparedStart overlap_start(const StatisticalObjective& obj, const Eigen::VectorXd& theta, const OverlapStartOptions& opt) {
  PreparedStart out{theta, {}};
  if (obj.options().metric != MetricKind::pr) return out;
  const Evaluation e = obj(theta);
  out.evaluations = 1;
  std::string flat;
  for (Eigen::Index j = 0; j < e.parts.size(); ++j)
    if (e.parts[j] > 2.0 - opt.saturation) flat += fmt::format("{}'{}' {:.3f}", flat.empty() ? "" : ", ", obj.responses()[static_cast<std::size_t>(j)].name, e.parts[j]);
  if (flat.empty()) return out;
  std::vector<Parameter> params = obj.parameters();
  for (std::size_t i = 0; i < params.size(); ++i) params[i].start = theta[static_cast<Eigen::Index>(i)];
  OptimizerOptions oo;
  oo.maxeval = opt.maxeval;
  oo.xtol_rel = 1e-4;
  oo.ftol_abs = 1e-10;
  const OptimizationResult m = minimize(params, [&obj](const Eigen::VectorXd& t) { return Evaluation{moment_mismatch(obj, t), {}}; }, oo);
  const Evaluation after = obj(m.theta);
  out.evaluations += m.evaluations + 1;
  if (!(after.value < e.value)) return out;
  std::string to;
  for (std::size_t i = 0; i < params.size(); ++i) to += fmt::format("{}{} = {:.6g}", i ? ", " : "", params[i].name, m.theta[static_cast<Eigen::Index>(i)]);
  out.theta = m.theta;
  out.note = fmt::format("the predicted and experimental PDFs did not overlap (PR {}: no gradient there); moved to a moment-matching "
                         "start ({}; objective {:.4g} -> {:.4g})", flat, to, e.value, after.value);
  return out;
}

}  // namespace smi::improve
