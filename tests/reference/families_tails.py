#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference values of the nine smi.dist families from SciPy 1.10 (Debian python3-scipy) for
tests/kernels/stats/test_families_tails.cpp: pdf, logpdf, cdf, logcdf, sf at body and tail
points (the quantiles of p = 1e-12 ... 1 - 1e-12, both sides), quantile(p) and isf(q).
Run: /usr/bin/python3 tests/reference/families_tails.py  ->  families_tails.csv
Rows: case,kind,arg,value (repr of doubles). The C++ test builds each case from the same
parameters (listed in CASES; the test keeps an identical table).

Where a SciPy 1.10 method falls back to a generic complement and so loses the tail, the reference
is made from SciPy's precise pieces instead (each place says so):
  - quantile/isf: SciPy's ppf/isf, refined by brentq on SciPy's cdf (p <= 1/2) or sf (upper
    side) when that root differs (lognorm, weibull_min and truncnorm isf go through 1 - q);
  - logcdf above the median: log1p(-sf) (SciPy takes log(cdf) of a cdf rounded near 1);
  - triang sf: the closed form (b - x)^2 / ((b - a)(b - c)) (SciPy computes 1 - cdf);
  - truncnorm cdf and sf: scipy.integrate.quad of norm.pdf from the nearer bound, over the
    normaliser Z from norm.sf/norm.cdf (SciPy's truncnorm takes differences of ndtr near a
    finite bound inside the body and loses 1e-5 relative at p = 1e-12)."""
import math, os
from scipy import integrate, optimize, stats

inf = math.inf
# case: (smi parameters as documented in the test, SciPy frozen distribution)
CASES = {
    "normal":        stats.norm(loc=1.5, scale=2.0),
    "lognormal":     stats.lognorm(s=0.6, scale=math.exp(0.3)),           # mu_log 0.3, sigma_log 0.6
    "uniform":       stats.uniform(loc=-1.0, scale=4.0),                  # [-1, 3]
    "truncnormal6":  stats.truncnorm(a=6.0, b=inf, loc=0.0, scale=1.0),   # N(0,1) on [6, inf)
    "truncnormal":   stats.truncnorm(a=-1.0, b=1.5, loc=1.0, scale=2.0),  # N(1,2) on [-1, 4]
    "truncnormal_lo": stats.truncnorm(a=-inf, b=-5.0, loc=0.0, scale=1.0),  # N(0,1) on (-inf, -5]
    "weibull":       stats.weibull_min(c=1.7, loc=0.5, scale=2.0),
    "weibull_k06":   stats.weibull_min(c=0.6, scale=1.0),
    "gumbel":        stats.gumbel_r(loc=1.0, scale=0.5),
    "gamma":         stats.gamma(a=2.5, scale=1.5),
    "gamma_k04":     stats.gamma(a=0.4, scale=2.0),
    "gamma_k30":     stats.gamma(a=30.0, scale=0.1, loc=1.0),
    "beta":          stats.beta(a=2.0, b=5.0),
    "beta_u":        stats.beta(a=0.5, b=0.7, loc=1.0, scale=2.0),        # on [1, 3]
    "beta_big":      stats.beta(a=20.0, b=3.0),
    "triangular":    stats.triang(c=1.0 / 3.0, loc=0.0, scale=3.0),      # lower 0, mode 1, upper 3
}
PS = [1e-12, 1e-9, 1e-6, 1e-3, 0.1, 0.5, 0.9, 1 - 1e-3, 1 - 1e-6, 1 - 1e-9, 1 - 1e-12]



def root(fun, x0):
    """The root of the increasing fun near x0 (brentq to full double precision)."""
    if fun(x0) == 0:
        return x0
    step = max(abs(x0) * 1e-6, 1e-300)
    lo, hi = x0, x0
    while fun(lo) > 0:
        lo -= step; step *= 2
    step = max(abs(x0) * 1e-6, 1e-300)
    while fun(hi) < 0:
        hi += step; step *= 2
    return optimize.brentq(fun, lo, hi, xtol=1e-300, rtol=8.9e-16, maxiter=500)


TRUNC = {"truncnormal6": (0.0, 1.0, 6.0, inf), "truncnormal": (1.0, 2.0, -1.0, 4.0),
         "truncnormal_lo": (0.0, 1.0, -inf, -5.0)}


def normal_mass(a, b):
    """Phi(b) - Phi(a) by quad for short intervals, complements otherwise (a <= b, standardised)."""
    if b - a < 1.0 and math.isfinite(a) and math.isfinite(b):
        return integrate.quad(stats.norm.pdf, a, b, epsabs=0, epsrel=1.2e-14, limit=200)[0]
    if a + b > 0:
        return stats.norm.sf(a) - stats.norm.sf(b)
    return stats.norm.cdf(b) - stats.norm.cdf(a)


def cdf(name, d, x):
    if name in TRUNC:
        m, s_, a, b = TRUNC[name]
        al, be, xi = (a - m) / s_, (b - m) / s_, (min(max(x, a), b) - m) / s_
        return normal_mass(al, xi) / normal_mass(al, be)
    return float(d.cdf(x))


def sf(name, d, x):
    if name in TRUNC:
        m, s_, a, b = TRUNC[name]
        al, be, xi = (a - m) / s_, (b - m) / s_, (min(max(x, a), b) - m) / s_
        return normal_mass(xi, be) / normal_mass(al, be)
    if name == "triangular":
        a, c, b = 0.0, 1.0, 3.0
        return (b - x) ** 2 / ((b - a) * (b - c)) if x > c else 1.0 - (x - a) ** 2 / ((b - a) * (c - a))
    return float(d.sf(x))


def quantile(name, d, p):
    x = float(d.ppf(p))
    lo, hi = d.support()
    if p <= 0.5:
        return x if x == lo else root(lambda t: cdf(name, d, max(t, lo)) - p, x)
    q = 1.0 - p
    return root(lambda t: q - sf(name, d, min(t, hi)), x)


def isf(name, d, q):
    x = float(d.isf(q))
    lo, hi = d.support()
    if q <= 0.5:
        return root(lambda t: q - sf(name, d, min(t, hi)), x)
    return root(lambda t: cdf(name, d, max(t, lo)) - (1.0 - q), x)


def value(name, d, kind, x):
    if kind == "cdf":
        return cdf(name, d, x)
    if kind == "sf":
        return sf(name, d, x)
    if kind == "logcdf":
        c = cdf(name, d, x)
        return math.log1p(-sf(name, d, x)) if c > 0.5 else (math.log(c) if name in TRUNC else float(d.logcdf(x)))
    return float(getattr(d, kind)(x))


here = os.path.dirname(os.path.abspath(__file__))
with open(os.path.join(here, "families_tails.csv"), "w") as f:
    f.write("case,kind,arg,value\n")
    for name, d in CASES.items():
        xs = []
        for p in PS:
            xq, xi = quantile(name, d, p), isf(name, d, p)
            f.write(f"{name},quantile,{p!r},{xq!r}\n")
            f.write(f"{name},isf,{p!r},{xi!r}\n")
            xs += [xq, xi]
        for x in sorted(set(xs)):
            for kind in ("pdf", "logpdf", "cdf", "logcdf", "sf"):
                f.write(f"{name},{kind},{x!r},{value(name, d, kind, x)!r}\n")
