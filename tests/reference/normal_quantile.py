#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference values of the standard normal quantile and CDF from SciPy (scipy.special.ndtri,
scipy.special.ndtr). Output: normal_quantile.csv (p, ndtri(p), x, ndtr(x)). Run with Debian's
/usr/bin/python3 (python3-scipy)."""
import csv, os
from scipy import special

here = os.path.dirname(os.path.abspath(__file__))
ps = [1e-300, 1e-100, 1e-20, 1e-10, 1e-5, 0.001, 0.02, 0.02425, 0.1, 0.3, 0.5, 0.7, 0.9, 0.97575, 0.99,
      0.999999, 1 - 1e-12]
xs = [-37.0, -20.0, -8.0, -3.0, -1.0, -0.1, 0.0, 0.5, 1.0, 2.5, 6.0, 8.0]
with open(os.path.join(here, "normal_quantile.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["kind", "arg", "value"])
    for p in ps:
        w.writerow(["quantile", repr(p), repr(float(special.ndtri(p)))])
    for x in xs:
        w.writerow(["cdf", repr(x), repr(float(special.ndtr(x)))])
