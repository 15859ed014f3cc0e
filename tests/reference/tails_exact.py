#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Exact tail values for tests/kernels/stats/test_tails_exact.cpp, by mpmath at
60 significant digits from the closed forms (every argument is the exact double the test uses):
  - triangular with its mode at a bound: cdf, logcdf, sf, quantile, isf near that bound
    (where 1 - (b - x)^2/... and b - sqrt(...) cancel);
  - logcdf far in the lower tail: weibull (z^k underflows), truncnormal, triangular;
  - the Gaussian KDE's tails: sf, logpdf, logcdf, quantile, isf far from the data, down to 1e-300.
Run: /usr/bin/python3 tests/reference/tails_exact.py  ->  tails_exact.csv  (python3-mpmath)
Rows: case,kind,arg,value (repr of doubles; the test keeps the same cases)."""
import os
import mpmath as mp

mp.mp.dps = 60
F = mp.mpf


def tri_cdf(a, c, b, x):
    a, c, b, x = F(a), F(c), F(b), F(x)
    if x <= a: return F(0)
    if x >= b: return F(1)
    if x <= c: return (x - a) ** 2 / ((b - a) * (c - a))
    return 1 - (b - x) ** 2 / ((b - a) * (b - c))


def tri_quantile(a, c, b, p):
    a, c, b, p = F(a), F(c), F(b), F(p)
    fc = (c - a) / (b - a)
    return a + mp.sqrt(p * (b - a) * (c - a)) if p < fc else b - mp.sqrt((1 - p) * (b - a) * (b - c))


def tri_isf(a, c, b, q):
    a, c, b, q = F(a), F(c), F(b), F(q)
    fc = (b - c) / (b - a)
    return b - mp.sqrt(q * (b - a) * (b - c)) if q <= fc else a + mp.sqrt((1 - q) * (b - a) * (c - a))


def Phi(z):
    return mp.ncdf(z)


rows = []


def add(case, kind, arg, value):
    rows.append(f"{case},{kind},{arg!r},{float(value)!r}")


# Triangular(0, 0, 3): mode at the lower bound; Triangular(0, 3, 3): mode at the upper bound.
for case, (a, c, b) in {"tri_lo": (0.0, 0.0, 3.0), "tri_hi": (0.0, 3.0, 3.0)}.items():
    for e in (2, 4, 6, 8, 10, 12, 14):
        d = 3.0 * 10.0 ** -e
        for x in (a + d, b - d):
            cdf = tri_cdf(a, c, b, x)
            add(case, "cdf", x, cdf)
            add(case, "sf", x, 1 - cdf)
            add(case, "logcdf", x, mp.log(cdf))
        p = 10.0 ** -e
        for pp in (p, 1 - p):
            add(case, "quantile", pp, tri_quantile(a, c, b, pp))
            add(case, "isf", pp, tri_isf(a, c, b, pp))
# Triangular(0, 1, 3): logcdf where (x - a)^2 underflows.
for x in (1e-100, 1e-160, 1e-200, 1e-300):
    add("tri", "logcdf", x, mp.log(tri_cdf(0.0, 1.0, 3.0, x)))

# Weibull(shape 1.7, scale 2, loc 0.5) and Weibull(0.6, 1): logcdf = log(1 - exp(-z^k)).
for case, (k, lam, loc) in {"weibull": (1.7, 2.0, 0.5), "weibull_k17": (1.7, 2.0, 0.0), "weibull_k06": (0.6, 1.0, 0.0)}.items():
    for z in (1e-3, 1e-10, 1e-15, 1e-50, 1e-100, 1e-150, 1e-250, 1e-300):
        x = loc + lam * z
        if x == loc: continue  # below the double resolution at loc
        zz = (F(x) - F(loc)) / F(lam)
        add(case, "logcdf", x, mp.log(-mp.expm1(-zz ** F(k))))

# Truncnormal: N(0, 1) on (-inf, -5]; N(0, 1) on [-20, 5]. logcdf = log((Phi(x) - Phi(a)) / Z).
for case, (lo, hi) in {"truncnormal_lo": (None, -5.0), "truncnormal_20": (-20.0, 5.0)}.items():
    Z = Phi(F(hi)) - (Phi(F(lo)) if lo is not None else 0)
    for x in (-6.0, -10.0, -15.0, -19.0, -19.9, -30.0, -37.0):
        if lo is not None and x <= lo: continue
        m = Phi(F(x)) - (Phi(F(lo)) if lo is not None else 0)
        add(case, "logcdf", x, mp.log(m / Z))

# KDE of {0, 1, 2.5} with h = 0.5: f = mean phi((x - d)/h)/h, F = mean Phi((x - d)/h).
data, h = [0.0, 1.0, 2.5], 0.5


def kde_sf(x):
    return sum(Phi((F(d) - F(x)) / F(h)) for d in data) / len(data)


def kde_cdf(x):
    return sum(Phi((F(x) - F(d)) / F(h)) for d in data) / len(data)


def kde_pdf(x):
    return sum(mp.npdf((F(x) - F(d)) / F(h)) for d in data) / (len(data) * F(h))


for m in (8, 10, 20, 30, 37):
    x = 2.5 + m * h
    add("kde", "sf", x, kde_sf(x))
for m in (10, 40, 100, 1000):
    add("kde", "logpdf", 2.5 + m * h, mp.log(kde_pdf(2.5 + m * h)))
    add("kde", "logpdf", 0.0 - m * h, mp.log(kde_pdf(0.0 - m * h)))
for m in (5, 9, 12, 30, 100, 1000):
    add("kde", "logcdf", 0.0 - m * h, mp.log(kde_cdf(0.0 - m * h)))
for q in (1e-20, 1e-50, 1e-100, 1e-200, 1e-300):
    add("kde", "isf", q, mp.findroot(lambda x: mp.log(kde_sf(x)) - mp.log(F(q)), F(2.5) + F(h) * mp.sqrt(-2 * mp.log(F(q)))))
    add("kde", "quantile", q, mp.findroot(lambda x: mp.log(kde_cdf(x)) - mp.log(F(q)), F(0.0) - F(h) * mp.sqrt(-2 * mp.log(F(q)))))

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "tails_exact.csv")
with open(out, "w") as f:
    f.write("case,kind,arg,value\n" + "\n".join(rows) + "\n")
print(f"{len(rows)} rows -> {out}")
