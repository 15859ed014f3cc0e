// SPDX-License-Identifier: MIT
// Surrogate screening (see screen_surrogate.hpp).
#include "kernels/surrogate/screen_surrogate.hpp"

#include <cmath>
#include <cstdio>

#include "kernels/surrogate/doe.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

namespace smi::surrogate::screen {

Eigen::MatrixXd surrogate_design(const std::vector<propagate::Input>& inputs, Eigen::Index runs, std::uint64_t seed) {
  const Eigen::Index k = static_cast<Eigen::Index>(inputs.size());
  doe::LhsOptions lo;
  lo.criterion = "none";  // a random LHS: an optimised one costs minutes at 300 x 46 for little gain here
  const Eigen::MatrixXd U = doe::lhs(runs, k, hash_label("surrogate-design") ^ seed, lo);
  Eigen::MatrixXd D(runs, k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const auto& in = inputs[static_cast<std::size_t>(j)];
    if (!in.dist) {
      D.col(j).setConstant(in.value);
      continue;
    }
    // Uniforms strictly inside (0, 1) so that unbounded quantiles stay finite.
    const Eigen::VectorXd u = U.col(j).array().max(1e-12).min(1.0 - 1e-12);
    D.col(j) = in.dist->quantile(u);
  }
  return D;
}

SurrogateResult screen_surrogate(const std::vector<propagate::Input>& inputs, const propagate::MatrixModel& model,
                                 const std::vector<std::string>& outputs, const Options& opt,
                                 const SurrogateOptions& sopt) {
  if (sopt.runs < kMinSurrogateRuns)
    throw InvalidArgument("runs must be at least " + std::to_string(kMinSurrogateRuns) + ", got " + std::to_string(sopt.runs));
  if (!(sopt.q2_min <= 1.0)) throw InvalidArgument("q2_min must be at most 1, got " + std::to_string(sopt.q2_min));
  SurrogateResult res;
  res.design = surrogate_design(inputs, sopt.runs, opt.seed);
  res.design_y = model(res.design);
  res.model_runs = sopt.runs;
  const std::size_t q = outputs.size();
  if (q == 0) throw InvalidArgument("no outputs to screen");
  if (res.design_y.rows() != sopt.runs || res.design_y.cols() != static_cast<Eigen::Index>(q))
    throw DimensionMismatch("model returned " + std::to_string(res.design_y.rows()) + " x " +
                            std::to_string(res.design_y.cols()) + " outputs for the " + std::to_string(sopt.runs) +
                            "-run surrogate design, expected " + std::to_string(sopt.runs) + " x " + std::to_string(q));
  std::vector<polyfit::Fit> fits;
  for (std::size_t o = 0; o < q; ++o) {
    const Eigen::VectorXd y = res.design_y.col(static_cast<Eigen::Index>(o));
    for (Eigen::Index i = 0; i < y.size(); ++i)
      if (!std::isfinite(y(i)))
        throw InvalidArgument("model output '" + outputs[o] + "' is not finite at run " + std::to_string(i + 1) +
                              " of the surrogate design");
    fits.push_back(polyfit::fit(res.design, y, sopt.basis));
    SurrogateFitInfo info;
    info.output = outputs[o];
    info.q2 = fits.back().q2;
    info.r2 = fits.back().r2;
    info.lambda = fits.back().lambda;
    info.terms = fits.back().terms;
    if (sopt.delta) {
      delta::Options dopt;
      dopt.classes = sopt.delta_classes;
      dopt.seed = opt.seed;
      const delta::Result d = delta::estimate(res.design, y, dopt);
      info.delta = d.delta;
      info.delta_floor = d.floor;
      info.delta_classes = d.classes;
    }
    res.fits.push_back(std::move(info));
  }
  const propagate::MatrixModel surrogate = [&](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(X.rows(), static_cast<Eigen::Index>(q));
    for (std::size_t o = 0; o < q; ++o) Y.col(static_cast<Eigen::Index>(o)) = fits[o].predict(X);
    return Y;
  };
  res.screening = screen(inputs, surrogate, outputs, opt);
  for (std::size_t o = 0; o < q; ++o) {
    const auto& f = res.fits[o];
    if (f.q2 < sopt.q2_min) {
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "the %s surrogate of '%s' predicts poorly: leave-one-out Q2 = %.3f < %.3g from %lld runs; its "
                    "screening ranks are not reliable: add runs%s, or screen the model itself (method = \"full\")",
                    polyfit::basis_name(sopt.basis), f.output.c_str(), f.q2, sopt.q2_min,
                    static_cast<long long>(sopt.runs),
                    sopt.basis == polyfit::Basis::linear ? ", use basis = \"quadratic\"" : "");
      res.screening[o].warnings.insert(res.screening[o].warnings.begin(), buf);
    }
  }
  return res;
}

}  // namespace smi::surrogate::screen
