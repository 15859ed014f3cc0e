// SPDX-License-Identifier: MIT
#include "kernels/stats/special.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "platform/core/normal.hpp"

namespace smi::stats {
namespace {
constexpr double kEps = 1e-16;
constexpr double kTiny = 1e-300;
constexpr double kInf = std::numeric_limits<double>::infinity();

// log of x^a e^-x / Γ(a): the common prefactor of the series and the continued fraction.
double gamma_log_prefactor(double a, double x) { return -x + a * std::log(x) - std::lgamma(a); }

// Σ x^k / (a (a+1) ... (a+k)): P(a, x) = sum · prefactor.
double gamma_series_sum(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int k = 1; k < 100000; ++k) {
    term *= x / (a + k);
    sum += term;
    if (std::abs(term) < std::abs(sum) * kEps) break;
  }
  return sum;
}

// The continued fraction of Γ(a, x)/(prefactor) (modified Lentz).
double gamma_cf(double a, double x) {
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < kEps) break;
  }
  return h;
}

double beta_cf(double a, double b, double x) {
  const double qab = a + b, qap = a + 1.0, qam = a - 1.0;
  double c = 1.0, d = 1.0 - qab * x / qap;
  if (std::abs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m < 100000; ++m) {
    const int m2 = 2 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < kEps) break;
  }
  return h;
}

// Gauss–Legendre 10-point nodes/weights on [-1, 1] (positive half; checked against numpy leggauss).
constexpr double kGlx[5] = {0.1488743389816312108848260, 0.4333953941292471907992659, 0.6794095682990244062343274,
                            0.8650633666889845107320967, 0.9739065285171717200779640};
constexpr double kGlw[5] = {0.2955242247147528701738930, 0.2692667193099963550912269, 0.2190863625159820439955349,
                            0.1494513491505805931457763, 0.0666713443086881375935688};
}  // namespace

GammaPQ gamma_pq(double a, double x) {
  if (x <= 0.0) return {0.0, 1.0, -kInf, 0.0};
  if (std::isinf(x)) return {1.0, 0.0, 0.0, -kInf};
  const double lp = gamma_log_prefactor(a, x);
  if (x < a + 1.0) {
    const double log_p = std::log(gamma_series_sum(a, x)) + lp;
    const double p = std::exp(log_p);
    return {p, 1.0 - p, log_p, std::log1p(-p)};
  }
  const double log_q = std::log(gamma_cf(a, x)) + lp;
  const double q = std::exp(log_q);
  return {1.0 - q, q, std::log1p(-q), log_q};
}

double gamma_p(double a, double x) { return gamma_pq(a, x).p; }
double gamma_q(double a, double x) { return gamma_pq(a, x).q; }

BetaInc beta_inc_both(double a, double b, double x) {
  if (x <= 0.0) return {0.0, 1.0, -kInf, 0.0};
  if (x >= 1.0) return {1.0, 0.0, 0.0, -kInf};
  const double lbt = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) {
    const double log_lo = lbt + std::log(beta_cf(a, b, x) / a);
    const double lo = std::exp(log_lo);
    return {lo, 1.0 - lo, log_lo, std::log1p(-lo)};
  }
  const double log_up = lbt + std::log(beta_cf(b, a, 1.0 - x) / b);
  const double up = std::exp(log_up);
  return {1.0 - up, up, std::log1p(-up), log_up};
}

double beta_inc(double a, double b, double x) { return beta_inc_both(a, b, x).lower; }

double student_t_quantile(double p, double df) {
  if (!(p > 0.0 && p < 1.0) || !(df > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  if (p == 0.5) return 0.0;
  // Two-sided tail q = P(|T| > t) = I_{df/(df+t²)}(df/2, 1/2), decreasing in t.
  const double q = 2.0 * std::min(p, 1.0 - p);
  auto tail = [&](double t) { return beta_inc_both(0.5 * df, 0.5, df / (df + t * t)).lower; };
  double lo = 0.0, hi = 1.0;
  while (tail(hi) > q && hi < 1e300) lo = hi, hi *= 4.0;
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double m = 0.5 * (lo + hi);
    (tail(m) > q ? lo : hi) = m;
  }
  const double t = 0.5 * (lo + hi);
  return p < 0.5 ? -t : t;
}

double log_normal_cdf(double x) {
  if (x > -5.0) return std::log1p(-0.5 * std::erfc(x / kSqrt2));
  // Φ(x) = φ(x) R(−x) with the Mills ratio R(t) = Φ(−t)/φ(t) by its continued fraction
  // R(t) = 1/(t + 1/(t + 2/(t + 3/(t + ...)))), evaluated bottom-up (converges fast for t >= 5).
  const double t = -x;
  double r = t;
  for (int k = 60; k >= 1; --k) r = t + k / r;
  return -0.5 * x * x - 0.91893853320467274178 - std::log(r);
}

double normal_mass(double a, double b) {
  if (!(a < b)) return 0.0;
  if (!std::isfinite(a) || !std::isfinite(b)) {
    if (a + b > 0.0) return normal_cdf(-a) - normal_cdf(-b);  // [a, ∞): the upper tail
    return normal_cdf(b) - normal_cdf(a);
  }
  return normal_mass_width(a, b - a);
}

double normal_mass_width(double a, double w) {
  if (!(w > 0.0)) return 0.0;
  if (!std::isfinite(w)) return normal_cdf(-a);
  // Work on the side where the tail values are small: mirror [a, a + w] to [−a − w, −a].
  if (a + 0.5 * w > 0.0) a = -a - w;
  const double fa = normal_cdf(a), fb = normal_cdf(a + w);
  const double d = fb - fa;
  if (d > 0.25 * fb) return d;  // at most 2 bits lost to the subtraction
  if (fb == 0.0) return 0.0;    // both ends beyond Φ's underflow (|x| > 38)
  // A narrow interval: ∫ φ by Gauss–Legendre over panels on which φ varies by at most e^{1/2};
  // the width w enters exactly (a − w, x − lower would round it away near a bound).
  const double scale = std::max(1.0, std::abs(a) + w);
  // (Here Φ(a) > ¾ Φ(a + w), which bounds w·|a| by about 0.3: one or a few panels.)
  const int panels = static_cast<int>(std::clamp(std::ceil(w * scale / 0.5), 1.0, 1e6));
  const double h = w / panels, hw = 0.5 * h;
  double s = 0.0;
  for (int k = 0; k < panels; ++k) {
    const double c = a + (k + 0.5) * h;
    for (int j = 0; j < 5; ++j) s += kGlw[j] * (normal_pdf(c - hw * kGlx[j]) + normal_pdf(c + hw * kGlx[j]));
  }
  return s * hw;
}

}  // namespace smi::stats
