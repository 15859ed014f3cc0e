#pragma once
// Special functions for the parametric families: regularised incomplete gamma and beta.

namespace smi {

/// P(a, x) = γ(a, x)/Γ(a), a > 0, x >= 0: series for x < a + 1, Lentz continued fraction otherwise.
double gamma_p(double a, double x);
/// I_x(a, b), the regularised incomplete beta, via its continued fraction (with the symmetry
/// I_x(a, b) = 1 − I_{1−x}(b, a) where that converges faster).
double beta_inc(double a, double b, double x);

}  // namespace smi
