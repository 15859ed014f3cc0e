// SPDX-License-Identifier: MIT
#include "kernels/improve/no_overlap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/kde.hpp"

namespace smi::improve {

std::string units_hint(double ratio) {
  if (!(std::isfinite(ratio) && ratio > 0.0)) return {};
  const double decades = std::log10(ratio);
  const double nearest = std::round(decades);
  if (nearest == 0.0 || std::abs(decades - nearest) > 0.15) return {};
  const std::string factor = fmt::format("{:g}", std::pow(10.0, std::abs(nearest)));
  return nearest > 0 ? fmt::format("the predictions are about {}x the data: are the inputs in the units the model expects?", factor)
                     : fmt::format("the predictions are about 1/{} of the data: are the inputs in the units the model expects?", factor);
}

std::vector<NoOverlap> find_no_overlap(const StatisticalObjective& obj, const Eigen::VectorXd& theta, const Eigen::VectorXd& parts,
                                       double pr_margin) {
  const MetricKind metric = obj.options().metric;
  if (metric == MetricKind::custom || parts.size() != static_cast<Eigen::Index>(obj.responses().size())) return {};
  std::vector<NoOverlap> rows;
  Eigen::MatrixXd Y;  // predicted only when some response is suspect
  for (std::size_t j = 0; j < obj.responses().size(); ++j) {
    const ResponseSpec& r = obj.responses()[j];
    const auto col = static_cast<Eigen::Index>(j);
    // PR below 0.9: over half of each distribution's mass is shared, so they overlap (and the usual
    // fit costs no extra model run here). Disjoint ranges read at least about 1 whatever the grid:
    // the experimental PDF's whole mass counts.
    if (metric == MetricKind::pr && parts[col] < 0.9) continue;
    // loglik: data outside the support floor densities; none floored in any evaluation, none now
    if (metric == MetricKind::loglik && obj.floored() == 0) continue;
    if (Y.size() == 0) Y = obj.predict(theta);
    const Eigen::VectorXd y = Y.col(col);
    if (metric == MetricKind::pr && parts[col] < 2.0 - pr_margin) {
      // PR on its grid can read far below 2 without any overlap: a prediction narrower than the
      // grid's step (a units error shrinks it 1000x) is integrated as almost nothing. Ranges
      // apart by more than 4 bandwidths of each side (KDE tails below 1e-4) are no overlap too.
      if (r.data.size() < 2 || !(y.maxCoeff() > y.minCoeff())) continue;
      const double hp = stats::bandwidth_by_name(y, obj.options().bandwidth), hd = stats::bandwidth_by_name(r.data, "silverman");
      const double gap = std::max(r.data.minCoeff() - y.maxCoeff(), y.minCoeff() - r.data.maxCoeff());
      if (!(gap > 4.0 * (hp + hd))) continue;
    }
    if (metric == MetricKind::loglik) {
      // every datum outside the predicted support: the KDE's density below the floor at all of them
      const double lo = y.minCoeff(), hi = y.maxCoeff();
      if (!(hi > lo) || r.data.size() == 0) continue;
      const Eigen::VectorXd f = stats::kde_pdf(y, stats::bandwidth_by_name(y, obj.options().bandwidth), r.data, 1);
      if ((f.array() > obj.options().density_floor).any()) continue;
    }
    NoOverlap row;
    row.response = r.name;
    row.metric = metric == MetricKind::pr ? "pr" : "loglik";
    row.value = parts[col];
    row.predicted_lo = y.minCoeff();
    row.predicted_hi = y.maxCoeff();
    double data_mean = 0.0;
    if (r.data.size() > 0) {
      row.measured_lo = r.data.minCoeff();
      row.measured_hi = r.data.maxCoeff();
      data_mean = r.data.mean();
    } else if (r.f_exp) {
      row.measured_lo = r.f_exp->quantile(0.001);
      row.measured_hi = r.f_exp->quantile(0.999);
      data_mean = r.f_exp->mean();
    }
    row.ratio = data_mean != 0.0 ? y.mean() / data_mean : std::nan("");
    row.units_hint = units_hint(row.ratio);
    rows.push_back(row);
  }
  return rows;
}

std::string describe(const std::vector<NoOverlap>& rows) {
  std::string s;
  for (const NoOverlap& r : rows) {
    if (!s.empty()) s += "; ";
    s += fmt::format("response '{}': the predictions [{:.4g}, {:.4g}] do not overlap the measurements [{:.4g}, {:.4g}] ({} = {:.4g})",
                     r.response, r.predicted_lo, r.predicted_hi, r.measured_lo, r.measured_hi, r.metric == "pr" ? "PR" : "-loglik",
                     r.value);
    if (!r.units_hint.empty()) s += "; " + r.units_hint;
  }
  if (!s.empty())
    s += " — no calibration within these ranges reaches the data: check the inputs' units and ranges and the model's outputs, "
         "or whether the model's form can produce such values at all (a model-form error: refine the model)";
  return s;
}

}  // namespace smi::improve
