// SPDX-License-Identifier: MIT
#pragma once
// Special functions for the parametric families: regularised incomplete gamma and beta, each
// with its complement computed directly (not as 1 − the other) so that upper tails keep their
// relative precision, and in log space for the log-CDFs.

namespace smi::stats {

/// Lower and upper regularised incomplete gamma, P + Q = 1, each to full relative precision.
struct GammaPQ {
  double p, q;          ///< P(a, x), Q(a, x)
  double log_p, log_q;  ///< their logarithms (finite where P or Q underflows)
};
/// a > 0, x >= 0: series for x < a + 1 (gives P, Q = 1 − P has no cancellation there), Lentz
/// continued fraction otherwise (gives Q).
GammaPQ gamma_pq(double a, double x);
/// P(a, x) = γ(a, x)/Γ(a).
double gamma_p(double a, double x);
/// Q(a, x) = Γ(a, x)/Γ(a), computed directly (upper tail).
double gamma_q(double a, double x);

/// I_x(a, b) and its complement 1 − I_x(a, b) = I_{1−x}(b, a), each from the continued fraction
/// on the side where it converges, the other by subtraction only where it is >= ~0.5.
struct BetaInc {
  double lower, upper;          ///< I_x(a, b), 1 − I_x(a, b)
  double log_lower, log_upper;  ///< their logarithms
};
BetaInc beta_inc_both(double a, double b, double x);
/// I_x(a, b), the regularised incomplete beta.
double beta_inc(double a, double b, double x);

/// Student's t quantile: t with P(T_df <= t) = p, p in (0, 1), df > 0, by bisection on the
/// incomplete beta (P(|T| > t) = I_{df/(df+t²)}(df/2, 1/2)), to about 1e-10 relative
/// (the incomplete beta's accuracy at df = 1).
double student_t_quantile(double p, double df);

/// log Φ(x) (standard normal), accurate for x far below 0 where Φ underflows.
double log_normal_cdf(double x);
/// Φ(b) − Φ(a) for a <= b to full relative precision: complements in the upper tail, and a
/// Gauss–Legendre integral of φ when a and b are so close that the difference cancels.
double normal_mass(double a, double b);
/// Φ(a + w) − Φ(a) with the width w >= 0 given on its own: near a truncation bound the width
/// (x − lower)/σ is known to full relative precision while a + w is not.
double normal_mass_width(double a, double w);

}  // namespace smi::stats
