// SPDX-License-Identifier: MIT
#pragma once
// The standard normal distribution: phi, Phi and Phi^-1 to full double precision.

namespace smi {

inline constexpr double kSqrt2 = 1.41421356237309504880;
inline constexpr double kInvSqrt2Pi = 0.39894228040143267794;

/// phi(x) = exp(-x^2/2) / sqrt(2 pi).
double normal_pdf(double x);
/// Phi(x) through erfc, accurate in both tails.
double normal_cdf(double x);
/// Phi^-1(p) for p in (0, 1); -inf at 0, +inf at 1, NaN outside.
/// Acklam's rational approximation (relative error 1.15e-9) refined by one Halley step on
/// erfc, which brings it to about 1e-15.
double normal_quantile(double p);

}  // namespace smi
