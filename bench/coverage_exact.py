#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Exact coverage of the 90 % profile-likelihood intervals of bench/calibration_coverage.lua's
problems (normal linear models): the profile likelihood ratio of a coefficient is
n ln(1 + T²/(n − p)) with T ~ t(n − p), of the error sd n(u − 1 − ln u) with u = RSS/(nσ²),
nRSS/σ² ~ χ²(n − p); an interval covers when that ratio is <= 2·delta. Prints markdown.
usage: coverage_exact.py"""
import numpy as np
from scipy import stats, optimize

LEVEL = 0.9


def deltas(n, k):
    plain = 0.5 * stats.chi2.ppf(LEVEL, 1)
    t = stats.t.ppf(0.5 * (1 + LEVEL), n - k)
    return plain, 0.5 * n * np.log1p(t * t / (n - k))


def coef(n, p, d):
    tc = np.sqrt((n - p) * np.expm1(2 * d / n))
    return 2 * stats.t.cdf(tc, n - p) - 1


def sd(n, p, d):
    f = lambda u: n * (u - 1 - np.log(u)) - 2 * d
    lo, hi = optimize.brentq(f, 1e-12, 1), optimize.brentq(f, 1, 100)
    return stats.chi2.cdf(hi * n, n - p) - stats.chi2.cdf(lo * n, n - p)


print("| problem | parameter | exact coverage, ½ χ²₁ | exact coverage, small-sample delta |")
print("|---|---|---|---|")
# (name, n, parameters fitted k, location parameters p, [(parameter, kind)])
for name, n, k, p, params in (("normal sample, n = 30", 30, 2, 1, (("mu", coef), ("sigma", sd))),
                              ("line, n = 25", 25, 3, 2, (("b0", coef), ("b1", coef), ("s", sd)))):
    plain, small = deltas(n, k)
    for pname, fn in params:
        print(f"| {name} | {pname} | {fn(n, p, plain):.4f} | {fn(n, p, small):.4f} |")
