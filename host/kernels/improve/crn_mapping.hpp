// SPDX-License-Identifier: MIT
#pragma once
// Common random numbers (CRN) for calibration objectives (docs/spec/algorithms.md §7).
// A fixed matrix Z of standard normals is drawn once and reused for every parameter vector;
// each input is mapped from its column of Z by the mean and standard deviation being tried, so
// the Monte-Carlo objective is a smooth function of θ and finite-difference gradients work.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

#include "kernels/stats/distribution.hpp"

namespace smi::improve {

/// How an input is parameterised by its (mean, std): spec §7 for normal, lognormal, uniform;
/// the other families of smi.dist as listed in kInputFamiliesHelp (calibrated mean/std where
/// they fix the distribution, with the shape fields of InputShape held fixed).
enum class InputFamily { normal, lognormal, uniform, constant, truncnormal, weibull, gumbel, gamma, beta, triangular };

/// What each family's calibrated (mean, std) mean and which fixed fields it takes: the text of
/// the error for an unknown family.
extern const char* const kInputFamiliesHelp;

/// The fixed (not calibrated) shape of an input of the families beyond normal/lognormal/uniform.
struct InputShape {
  double lower = -std::numeric_limits<double>::infinity();  ///< truncnormal, beta (beta default 0)
  double upper = std::numeric_limits<double>::infinity();   ///< truncnormal, beta (beta default 1)
  double loc = 0.0;                                         ///< weibull, gamma: the support's lower end
  double mode_at = 0.5;  ///< triangular: (mode − lower)/(upper − lower), in [0, 1]
};

/// The distribution of an input of `family` with calibrated (mean, std) and fixed `shape`;
/// throws InvalidArgument naming `what` when (mean, std) is impossible for the family (e.g. a
/// beta std above what [lower, upper] allows). Constant and std = 0 give nullptr.
stats::DistributionPtr input_distribution(InputFamily family, double mean, double std, const InputShape& shape, std::string_view what);

/// "normal" -> InputFamily::normal ...; throws InvalidArgument naming `what` and the choices.
InputFamily parse_family(std::string_view name, std::string_view what);
std::string family_name(InputFamily f);

/// Log-space parameters of a lognormal with the given mean and std (mean > 0, std >= 0):
/// σ_ln = sqrt(ln(1 + s²/μ²)), μ_ln = ln μ − σ_ln²/2.
struct LognormalParams {
  double mu_ln;
  double sigma_ln;
};
LognormalParams lognormal_params(double mean, double std);

/// Bounds of the uniform with the given mean and std: mean ∓ √3·std.
struct UniformBounds {
  double lower;
  double upper;
};
UniformBounds uniform_bounds(double mean, double std);

/// Maps standard normals z to samples of `family` with the given mean and std. Throws
/// InvalidArgument naming `what` for std < 0, non-finite values, or a lognormal with mean <= 0.
/// The families beyond normal/lognormal/uniform map through their quantile (isf above the
/// median, so both tails keep their precision) with `shape` fixed.
Eigen::VectorXd map_standard_normal(InputFamily family, double mean, double std, const Eigen::Ref<const Eigen::VectorXd>& z,
                                    std::string_view what, const InputShape& shape = {});

/// How the fixed standard-normal matrix is made.
enum class CrnKind {
  random,    ///< iid N(0,1) from smi::Rng(seed)
  quantiles  ///< z_i = Φ⁻¹((i − ½)/n) in column 1; further columns are seeded permutations of it
};

/// The n×k CRN matrix. Same seed, same matrix.
Eigen::MatrixXd crn_matrix(Eigen::Index n, Eigen::Index k, std::uint64_t seed, CrnKind kind = CrnKind::random);

}  // namespace smi::improve
