#pragma once
// Common random numbers (CRN) for calibration objectives (shared/spec/algorithms.md §7).
// A fixed matrix Z of standard normals is drawn once and reused for every parameter vector;
// each input is mapped from its column of Z by the mean and standard deviation being tried, so
// the Monte-Carlo objective is a smooth function of θ and finite-difference gradients work.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>

namespace smi::improve {

/// How an input is parameterised by its (mean, std): spec §7.
enum class InputFamily { normal, lognormal, uniform, constant };

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
Eigen::VectorXd map_standard_normal(InputFamily family, double mean, double std, const Eigen::Ref<const Eigen::VectorXd>& z,
                                    std::string_view what);

/// How the fixed standard-normal matrix is made.
enum class CrnKind {
  random,    ///< iid N(0,1) from smi::Rng(seed)
  quantiles  ///< z_i = Φ⁻¹((i − ½)/n) in column 1; further columns are seeded permutations of it
};

/// The n×k CRN matrix. Same seed, same matrix.
Eigen::MatrixXd crn_matrix(Eigen::Index n, Eigen::Index k, std::uint64_t seed, CrnKind kind = CrnKind::random);

}  // namespace smi::improve
