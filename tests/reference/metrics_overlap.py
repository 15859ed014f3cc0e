#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""PR = integral |f - g| and the intersection area = integral min(f, g) of pairs of analytic pdfs
that are infinite at a support bound, narrow or skewed, by scipy.integrate.quad (QUADPACK qags,
which extrapolates over endpoint singularities) on the pieces between the pdf crossings
(located by brentq on a dense quantile scan) and the support bounds.
For tests/kernels/stats/test_metrics.cpp. Run: /usr/bin/python3 tests/reference/metrics_overlap.py
Output: metrics_overlap.csv with rows  pair,pr,intersection  (the C++ test builds each pair
from the same parameters: see PAIRS)."""
import math, os
import numpy as np
from scipy import integrate, optimize, stats

PAIRS = {
    # pair: (a, b) as SciPy frozen distributions; smi parameters in comments
    "gamma05_gamma2": (stats.gamma(0.5), stats.gamma(2.0)),                      # gamma{shape=.5, scale=1} vs {shape=2}
    "gamma03_gamma03s15": (stats.gamma(0.3), stats.gamma(0.3, scale=1.5)),        # both infinite at 0
    "beta05_beta2": (stats.beta(0.5, 0.5), stats.beta(2.0, 2.0)),                 # infinite at both ends
    "weibull07_lognormal": (stats.weibull_min(0.7), stats.lognorm(s=0.8)),        # weibull{shape=.7, scale=1}, lognormal{mu_log=0, sigma_log=.8}
    "normal_narrow": (stats.norm(0.0, 1.0), stats.norm(0.0, 0.01)),
    "lognormal_mode009_gamma": (stats.lognorm(s=1.55), stats.gamma(2.0, scale=0.5)),  # mode exp(-1.55^2) = 0.0905
    "truncnormal_uniform": (stats.truncnorm(0.0, math.inf), stats.uniform(0.0, 2.0)),  # N(0,1) on [0, inf) vs U(0, 2)
}


def scan(d):
    t = np.linspace(-34.5, 34.5, 2001)
    p = 1.0 / (1.0 + np.exp(-t))
    x = np.where(t <= 0, d.ppf(p), d.isf(1.0 / (1.0 + np.exp(t))))
    return x[np.isfinite(x)]


def overlap(a, b):
    diff = lambda x: a.pdf(x) - b.pdf(x)
    bounds = [v for d in (a, b) for v in d.support() if math.isfinite(v)]
    xs = np.unique(np.concatenate([scan(a), scan(b), bounds]))
    cuts = set(bounds)
    prev = None
    for x in xs:
        v = diff(x)
        if not math.isfinite(v) or v == 0:
            continue
        if prev is not None and (v > 0) != (prev[1] > 0):
            cuts.add(optimize.brentq(diff, prev[0], x, xtol=1e-300, rtol=8.9e-16))
        prev = (x, v)
    lo = min(min(d.support()[0] for d in (a, b)), min(xs))
    hi = max(max(d.support()[1] for d in (a, b)), max(xs))
    pts = sorted(cuts | {lo, hi})
    l1 = inter = 0.0
    for u, v in zip(pts[:-1], pts[1:]):
        if not u < v:
            continue
        ia = integrate.quad(a.pdf, u, v, epsabs=1e-15, epsrel=1e-13, limit=500)[0]
        ib = integrate.quad(b.pdf, u, v, epsabs=1e-15, epsrel=1e-13, limit=500)[0]
        l1 += abs(ia - ib)
        inter += min(ia, ib)
    return l1, inter


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "metrics_overlap.csv"), "w") as f:
        f.write("pair,pr,intersection\n")
        for name, (a, b) in PAIRS.items():
            l1, inter = overlap(a, b)
            f.write(f"{name},{l1!r},{inter!r}\n")
