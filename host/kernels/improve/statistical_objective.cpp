// SPDX-License-Identifier: MIT
#include "kernels/improve/statistical_objective.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/kde_coarse_grid.hpp"
#include "kernels/stats/metrics.hpp"
#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::improve {

MetricKind parse_metric(std::string_view name) {
  if (name == "pr") return MetricKind::pr;
  if (name == "loglik") return MetricKind::loglik;
  throw InvalidArgument(fmt::format("unknown metric \"{}\" (use \"pr\", \"loglik\" or a function)", name));
}

namespace {

std::string theta_text(const std::vector<Parameter>& p, const Eigen::VectorXd& t) {
  std::string s;
  for (std::size_t i = 0; i < p.size(); ++i) s += fmt::format("{}{} = {:.8g}", i ? ", " : "", p[i].name, t[static_cast<Eigen::Index>(i)]);
  return s;
}

/// Bandwidth of a predicted sample by rule, with an error that says what to do about a constant
/// output (a KDE of ties is a point mass).
double predicted_bandwidth(ConstVec y, const std::string& rule, const std::string& response) {
  const double lo = y.minCoeff(), hi = y.maxCoeff();
  if (!(hi > lo))
    throw InvalidArgument(fmt::format("response '{}': the model output is constant ({}) over the CRN sample, so it has no density "
                                      "(check that the calibrated inputs reach the model)", response, lo));
  return stats::bandwidth_by_name(y, rule);
}

/// The experimental PDF of measured points where none is given: the Gaussian KDE with the
/// normal-reference bandwidth, for the data and for every resample of them alike.
stats::DistributionPtr data_kde(const Eigen::VectorXd& x) { return stats::make_kde(x, stats::bandwidth_normal_reference(x)); }

/// The same doubles bit for bit (0.0 and -0.0 differ; a NaN θ never reaches the model).
bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
  return true;
}

}  // namespace

StatisticalObjective::StatisticalObjective(std::vector<InputSpec> inputs, std::vector<ResponseSpec> responses,
                                           std::vector<Parameter> params, Model model, StatisticalOptions opt,
                                           CustomMetric custom)
    : inputs_(std::move(inputs)),
      responses_(std::move(responses)),
      params_(std::move(params)),
      model_(std::move(model)),
      opt_(std::move(opt)),
      custom_(std::move(custom)) {
  validate_parameters(params_);
  if (inputs_.empty()) throw InvalidArgument("no inputs: give at least one input distribution");
  if (responses_.empty()) throw InvalidArgument("no data: give at least one response with experimental data");
  if (opt_.n < kMinCrnSize) throw InvalidArgument(fmt::format("n (CRN sample size) must be >= {}, got {}", kMinCrnSize, opt_.n));
  if (opt_.grid_nodes < kMinGridNodes)
    throw InvalidArgument(fmt::format("grid_nodes must be >= {}, got {}", kMinGridNodes, opt_.grid_nodes));
  if (opt_.metric == MetricKind::custom && !custom_) throw InvalidArgument("metric is custom but no metric function was given");
  const int k = static_cast<int>(params_.size());
  std::vector<int> used(static_cast<std::size_t>(k), 0);
  for (const InputSpec& in : inputs_) {
    const std::string who = fmt::format("input '{}'", in.name);
    for (int idx : {in.mean_param, in.std_param}) {
      if (idx >= k) throw InvalidArgument(fmt::format("{}: parameter index {} out of range", who, idx));
      if (idx >= 0) ++used[static_cast<std::size_t>(idx)];
    }
    // Check the parameterisation over the whole box now rather than at an unlucky θ later.
    const double mlo = in.mean_param >= 0 ? params_[static_cast<std::size_t>(in.mean_param)].lower : in.mean;
    const double slo = in.std_param >= 0 ? params_[static_cast<std::size_t>(in.std_param)].lower : in.std;
    if (in.family == InputFamily::lognormal && !(mlo > 0.0))
      throw InvalidArgument(fmt::format("{}: lognormal needs mean > 0 everywhere, but its mean can be {} (raise the lower bound above 0 "
                                        "or use \"normal\")", who, mlo));
    if (!(slo >= 0.0))
      throw InvalidArgument(in.std_param >= 0 ? fmt::format("{}: std must be >= 0, but its range starts at {} (raise the lower bound to >= 0)", who, slo)
                                              : fmt::format("{}: std must be >= 0, got {}", who, slo));
  }
  for (int i = 0; i < k; ++i)
    if (used[static_cast<std::size_t>(i)] != 1)
      throw InvalidArgument(fmt::format("parameter '{}' is used by {} input moments (must be exactly 1)", params_[static_cast<std::size_t>(i)].name,
                                        used[static_cast<std::size_t>(i)]));
  for (ResponseSpec& r : responses_) {
    if (r.data.size() > 0) require_finite(r.data, fmt::format("data of response '{}'", r.name));
    if (opt_.metric != MetricKind::custom && r.data.size() < 2 && !(opt_.metric == MetricKind::pr && r.f_exp))
      throw InvalidArgument(fmt::format("response '{}': need at least 2 experimental data, got {}", r.name, r.data.size()));
  }
  z_ = crn_matrix(opt_.n, static_cast<Eigen::Index>(inputs_.size()), opt_.seed, opt_.crn);
  Eigen::VectorXd start(k);
  for (int i = 0; i < k; ++i) start[i] = params_[static_cast<std::size_t>(i)].start;
  prepare_responses(start);
}

void StatisticalObjective::prepare_responses(const Eigen::VectorXd& start) {
  f_exp_grid_.clear();
  exp_outside_.clear();
  if (opt_.metric != MetricKind::pr) return;
  Eigen::MatrixXd y0;  // one model run at the start fixes the default grids
  for (ResponseSpec& r : responses_) {
    if (!r.f_exp) {
      r.f_exp = data_kde(r.data);
      r.f_exp_from_data = true;
    }
    if (!r.grid) {
      if (y0.size() == 0) y0 = run_model(start);
      const Eigen::Index j = &r - responses_.data();
      const Eigen::VectorXd y = y0.col(j);
      const double hp = predicted_bandwidth(y, opt_.bandwidth, r.name);
      double lo = y.minCoeff() - 6.0 * hp, hi = y.maxCoeff() + 6.0 * hp;
      if (auto* kde = dynamic_cast<const stats::Kde*>(r.f_exp.get())) {
        lo = std::min(lo, kde->data().minCoeff() - 6.0 * kde->bandwidth());
        hi = std::max(hi, kde->data().maxCoeff() + 6.0 * kde->bandwidth());
      } else {
        lo = std::min(lo, r.f_exp->quantile(1e-10));
        hi = std::max(hi, r.f_exp->quantile(1.0 - 1e-10));
      }
      r.grid = stats::Grid{lo, hi, opt_.grid_nodes};
    }
    r.grid->validate();
    OnGrid e = on_grid(*r.f_exp, *r.grid);
    f_exp_grid_.push_back(std::move(e.pdf));
    exp_outside_.push_back(e.outside);
  }
}

StatisticalObjective::OnGrid StatisticalObjective::on_grid(const stats::Distribution& f, const stats::Grid& g) {
  return {stats::pdf_grid(f, g), std::max(0.0, f.cdf(g.lo)) + std::max(0.0, 1.0 - f.cdf(g.hi))};
}

StatisticalObjective::OnGrid StatisticalObjective::predicted_on_grid(Eigen::Index j, const Eigen::VectorXd& y) const {
  const ResponseSpec& r = responses_[static_cast<std::size_t>(j)];
  const stats::Grid& g = *r.grid;
  const double h = predicted_bandwidth(y, opt_.bandwidth, r.name);
  Eigen::VectorXd ends(2);
  ends << g.lo, g.hi;
  const Eigen::VectorXd F = stats::kde_cdf(y, h, ends, 1);
  return {stats::kde_pdf_resolved(y, h, g, opt_.threads), std::max(0.0, F[0]) + std::max(0.0, 1.0 - F[1])};
}

double StatisticalObjective::pr_part(Eigen::Index j, const OnGrid& predicted, const Eigen::VectorXd& exp_pdf, double exp_outside) const {
  return stats::l1_area_on_grid(exp_pdf, predicted.pdf, *responses_[static_cast<std::size_t>(j)].grid) + predicted.outside + exp_outside;
}

std::vector<double> StatisticalObjective::pr_sums_against(const Eigen::VectorXd& theta, const std::vector<std::vector<Eigen::VectorXd>>& data_sets,
                                                          int threads) const {
  if (opt_.metric != MetricKind::pr) throw InvalidArgument("pr_sums_against: the objective's metric is not PR");
  const Eigen::MatrixXd Y = run_model(theta);
  std::vector<OnGrid> predicted;
  for (Eigen::Index j = 0; j < Y.cols(); ++j) predicted.push_back(predicted_on_grid(j, Y.col(j)));
  std::vector<double> sums(data_sets.size(), std::nan(""));
  pool::parallel_for(static_cast<long>(data_sets.size()), threads, [&](long b) {
    const auto& d = data_sets[static_cast<std::size_t>(b)];
    if (d.size() != responses_.size()) throw DimensionMismatch(fmt::format("{} data sets for {} responses", d.size(), responses_.size()));
    double sum = 0.0;
    try {
      for (std::size_t j = 0; j < d.size(); ++j) {
        require_finite(d[j], fmt::format("data of response '{}'", responses_[j].name));
        const OnGrid e = on_grid(*data_kde(d[j]), *responses_[j].grid);
        sum += pr_part(static_cast<Eigen::Index>(j), predicted[j], e.pdf, e.outside);
      }
    } catch (const InvalidArgument&) {
      return;  // a degenerate set (all its points equal: no bandwidth) stays NaN
    }
    sums[static_cast<std::size_t>(b)] = sum;
  });
  return sums;
}

std::vector<std::pair<double, double>> StatisticalObjective::input_moments(const Eigen::VectorXd& theta) const {
  if (theta.size() != static_cast<Eigen::Index>(params_.size()))
    throw DimensionMismatch(fmt::format("θ has {} values for {} parameters", theta.size(), params_.size()));
  std::vector<std::pair<double, double>> m;
  for (const InputSpec& in : inputs_)
    m.emplace_back(in.mean_param >= 0 ? theta[in.mean_param] : in.mean, in.std_param >= 0 ? theta[in.std_param] : in.std);
  return m;
}

Eigen::MatrixXd StatisticalObjective::inputs_at(const Eigen::VectorXd& theta) const {
  const auto m = input_moments(theta);
  Eigen::MatrixXd X(opt_.n, static_cast<Eigen::Index>(inputs_.size()));
  for (std::size_t j = 0; j < inputs_.size(); ++j)
    X.col(static_cast<Eigen::Index>(j)) =
        map_standard_normal(inputs_[j].family, m[j].first, m[j].second, z_.col(static_cast<Eigen::Index>(j)),
                            fmt::format("input '{}'", inputs_[j].name), inputs_[j].shape);
  return X;
}

bool StatisticalObjective::cached_output(const Eigen::VectorXd& theta, Eigen::MatrixXd& Y) const {
  std::lock_guard<std::mutex> lock(cache_->mutex);
  auto& e = cache_->entries;
  for (auto it = e.rbegin(); it != e.rend(); ++it)
    if (same_bits(it->first, theta)) {
      Y = it->second;
      return true;
    }
  return false;
}

void StatisticalObjective::cache_output(const Eigen::VectorXd& theta, const Eigen::MatrixXd& Y) const {
  std::lock_guard<std::mutex> lock(cache_->mutex);
  auto& e = cache_->entries;
  if (e.size() >= OutputCache::kEntries) e.erase(e.begin());
  e.emplace_back(theta, Y);
}

Eigen::MatrixXd StatisticalObjective::run_model(const Eigen::VectorXd& theta) const {
  Eigen::MatrixXd Y;
  if (cached_output(theta, Y)) return Y;
  const Eigen::MatrixXd X = inputs_at(theta);
  Y = model_(X);
  ++*runs_;
  ++*passes_;
  check_output(Y, X.rows(), theta);
  cache_output(theta, Y);
  return Y;
}

void StatisticalObjective::check_output(const Eigen::MatrixXd& Y, Eigen::Index rows, const Eigen::VectorXd& theta) const {
  if (Y.rows() != rows || Y.cols() != static_cast<Eigen::Index>(responses_.size()))
    throw DimensionMismatch(fmt::format("the model returned {}×{} outputs for {} samples and {} responses", Y.rows(), Y.cols(), rows,
                                        responses_.size()));
  for (Eigen::Index j = 0; j < Y.cols(); ++j)
    for (Eigen::Index i = 0; i < Y.rows(); ++i)
      if (!std::isfinite(Y(i, j)))
        throw InvalidArgument(fmt::format("the model returned {} for response '{}' at sample {} (θ: {})", Y(i, j),
                                          responses_[static_cast<std::size_t>(j)].name, i % opt_.n + 1, theta_text(params_, theta)));
}

void StatisticalObjective::set_model_differences(bool central, double rel_step) {
  if (!(rel_step > 0.0 && rel_step < kMaxModelStep) || !std::isfinite(rel_step))
    throw InvalidArgument(fmt::format("model_step must be a relative step in (0, {}), got {}", kMaxModelStep, rel_step));
  diff_central_ = central;
  diff_step_ = rel_step;
}

std::pair<Eigen::MatrixXd, std::vector<Eigen::MatrixXd>> StatisticalObjective::predict_with_jacobian(const Eigen::VectorXd& theta) const {
  const Eigen::MatrixXd X = inputs_at(theta);
  if (jacobian_) {
    Eigen::MatrixXd Y = run_model(theta);
    return {std::move(Y), model_jacobian(X)};
  }
  if (diff_step_ > 0.0) return differences(theta, X);
  throw InvalidArgument("the model has no gradient and no model differences are set");
}

std::pair<Eigen::MatrixXd, std::vector<Eigen::MatrixXd>> StatisticalObjective::differences(const Eigen::VectorXd& theta,
                                                                                           const Eigen::MatrixXd& X) const {
  const Eigen::Index N = X.rows(), k = X.cols();
  std::vector<Eigen::Index> cols;  // inputs that carry a calibrated parameter
  for (std::size_t j = 0; j < inputs_.size(); ++j)
    if (inputs_[j].mean_param >= 0 || inputs_[j].std_param >= 0) cols.push_back(static_cast<Eigen::Index>(j));
  // The outputs at X itself are usually known: SLSQP asks for the gradient where it has just
  // evaluated the value. Then the batch holds only the perturbed blocks.
  Eigen::MatrixXd Y0;
  const Eigen::Index base = cached_output(theta, Y0) ? 0 : 1;
  const Eigen::Index per = diff_central_ ? 2 : 1;
  const Eigen::Index blocks = base + per * static_cast<Eigen::Index>(cols.size());
  Eigen::MatrixXd batch(N * blocks, k);
  if (base) batch.topRows(N) = X;
  std::vector<double> h(cols.size());
  for (std::size_t c = 0; c < cols.size(); ++c) {
    const Eigen::VectorXd x = X.col(cols[c]);
    const double sd = stddev(x), scale = std::max(sd, 1e-6 * std::abs(x.mean()));
    h[c] = diff_step_ * (scale > 0.0 ? scale : 1.0);
    for (Eigen::Index s = 0; s < per; ++s) {
      const Eigen::Index b = base + per * static_cast<Eigen::Index>(c) + s;
      batch.middleRows(b * N, N) = X;
      batch.middleRows(b * N, N).col(cols[c]).array() += (s == 0 ? h[c] : -h[c]);
    }
  }
  const Eigen::MatrixXd out = model_(batch);
  ++*runs_;
  *passes_ += static_cast<long>(blocks);
  check_output(out, batch.rows(), theta);
  if (base) {
    Y0 = out.topRows(N);
    cache_output(theta, Y0);
  }
  const Eigen::Index R = out.cols();
  std::vector<Eigen::MatrixXd> J(static_cast<std::size_t>(R), Eigen::MatrixXd::Zero(N, k));
  for (std::size_t c = 0; c < cols.size(); ++c) {
    const Eigen::Index up = (base + per * static_cast<Eigen::Index>(c)) * N;
    for (Eigen::Index r = 0; r < R; ++r) {
      if (diff_central_)
        J[static_cast<std::size_t>(r)].col(cols[c]) = (out.col(r).segment(up, N) - out.col(r).segment(up + N, N)) / (2.0 * h[c]);
      else
        J[static_cast<std::size_t>(r)].col(cols[c]) = (out.col(r).segment(up, N) - Y0.col(r)) / h[c];
    }
  }
  return {std::move(Y0), std::move(J)};
}

Evaluation StatisticalObjective::operator()(const Eigen::VectorXd& theta) const {
  const Eigen::MatrixXd Y = run_model(theta);
  if (opt_.metric == MetricKind::custom) return custom_(Y);
  Evaluation e;
  e.parts.resize(Y.cols());
  for (Eigen::Index j = 0; j < Y.cols(); ++j) {
    const ResponseSpec& r = responses_[static_cast<std::size_t>(j)];
    const Eigen::VectorXd y = Y.col(j);
    if (opt_.metric == MetricKind::pr) {
      const auto k = static_cast<std::size_t>(j);
      e.parts[j] = pr_part(j, predicted_on_grid(j, y), f_exp_grid_[k], exp_outside_[k]);
    } else {
      const double h = predicted_bandwidth(y, opt_.bandwidth, r.name);
      const Eigen::VectorXd f = stats::kde_pdf(y, h, r.data, 1);
      double s = 0.0;
      for (Eigen::Index i = 0; i < f.size(); ++i) {
        if (!(f[i] > opt_.density_floor)) ++*floored_;
        s += std::log(std::max(f[i], opt_.density_floor));
      }
      e.parts[j] = -s;
    }
  }
  e.value = e.parts.sum();
  return e;
}

std::pair<double, double> ResponseSpec::moments() const {
  if (f_exp && !f_exp_from_data) return {f_exp->mean(), f_exp->stddev()};  // the analyst's PDF speaks for the data
  if (data.size() >= 2) return {data.mean(), stddev(data)};
  return {0.0, 0.0};
}

Eigen::VectorXd StatisticalObjective::summaries(const Eigen::VectorXd& theta) const {
  const Eigen::MatrixXd Y = run_model(theta);
  Eigen::VectorXd out(4 * Y.cols());
  for (Eigen::Index j = 0; j < Y.cols(); ++j) {
    const ResponseSpec& r = responses_[static_cast<std::size_t>(j)];
    auto [m, sd] = r.moments();
    if (!(sd > 0.0) || !std::isfinite(sd) || !std::isfinite(m)) {
      m = Y.col(j).mean();
      sd = std::max(1e-300, stddev(Y.col(j)));
    }
    // Sample means of the probabilists' Hermite polynomials He1..He4 of z = (y − m)/sd, each
    // divided by sqrt(p!): averages (smooth in θ on CRN, unlike sample quantiles, whose
    // derivative is one sample's), of unit variance per datum when the data are normal.
    const Eigen::ArrayXd z = (Y.col(j).array() - m) / sd, z2 = z * z;
    out[4 * j + 0] = z.mean();
    out[4 * j + 1] = (z2 - 1.0).mean() / std::sqrt(2.0);
    out[4 * j + 2] = (z2 * z - 3.0 * z).mean() / std::sqrt(6.0);
    out[4 * j + 3] = (z2 * z2 - 6.0 * z2 + 3.0).mean() / std::sqrt(24.0);
  }
  return out;
}

StatisticalObjective StatisticalObjective::with_data(const std::vector<Eigen::VectorXd>& data) const {
  if (data.size() != responses_.size())
    throw DimensionMismatch(fmt::format("{} data sets for {} responses", data.size(), responses_.size()));
  StatisticalObjective o = *this;
  for (std::size_t j = 0; j < data.size(); ++j) {
    ResponseSpec& r = o.responses_[j];
    if (r.data.size() < 2)
      throw InvalidArgument(fmt::format("response '{}': its experimental PDF was given without its points, so it cannot be resampled (give "
                                        "data = {{{} = {{points = vec, pdf = dist}}}})", r.name, r.name));
    require_finite(data[j], fmt::format("data of response '{}'", r.name));
    r.data = data[j];
    r.f_exp.reset();  // a resample's PDF is the plain KDE of its points
  }
  Eigen::VectorXd start(static_cast<Eigen::Index>(params_.size()));
  for (std::size_t i = 0; i < params_.size(); ++i) start[static_cast<Eigen::Index>(i)] = params_[i].start;
  o.prepare_responses(start);  // grids are already fixed: no model run here
  return o;
}

}  // namespace smi::improve
