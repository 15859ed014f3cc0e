#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference values for tests/kernels/improve/test_profile_intervals.cpp:
SciPy's Student t quantiles and the small-sample profile delta n/2 ln(1 + t²/(n − k)).
The output below is stored in the test as literals.
usage: student_t_quantile.py"""
import numpy as np
from scipy import stats

for p, df in ((0.95, 22), (0.975, 3), (0.05, 1), (0.999, 2.5), (0.6, 100)):
    print(f"t {p} {df} {stats.t.ppf(p, df)!r}")
for level, n, k in ((0.9, 25, 3), (0.95, 30, 2)):
    t = stats.t.ppf(0.5 * (1 + level), n - k)
    print(f"delta {level} {n} {k} {0.5 * n * np.log1p(t * t / (n - k))!r}")
# output (scipy 1.10.1):
# t 0.95 22 1.717144374380242
# t 0.975 3 3.182446305284263
# t 0.05 1 -6.313751514800938
# t 0.999 2.5 13.822193110834316
# t 0.6 100 0.25402218245699415
# delta 0.9 25 3 1.5721830735804492
# delta 0.95 30 2 2.094552536206453
