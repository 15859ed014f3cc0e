#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference for the measured PR tolerance (host/kernels/improve/pr_tolerance.hpp), for
tests/kernels/improve/test_pr_tolerance.cpp: the standard deviation (and mean) of the summed
probability residual  sum_r integral |f_exp,r - f_pre,r| dy  over bootstrap resamples of 9 data
rows (paired: one index per row for both responses), each resample's f_exp the Gaussian KDE of
its points with the normal-reference bandwidth (4/(3n))^(1/5) sd (sd with n - 1), integrated by
the trapezoid rule on the test's grids.
The prediction is written in closed form: the model y1 = a, y2 = a + b with a ~ N(10, 1) and
b ~ N(5, 0.5) gives normal outputs, and the kernel's KDE of N of them (the same bandwidth rule)
is, to first order, the normal with the bandwidth's variance added. 200000 resamples (NumPy's
generator, independent of the kernel's), so the reference's own Monte Carlo error (0.16 % of
the standard deviation) is negligible against the test's.
Output: pr_tolerance.json. Run with Debian's /usr/bin/python3 (python3-numpy)."""
import json, os
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
rows = [(9.12, 14.31), (10.85, 16.02), (9.71, 14.48), (11.40, 16.95), (10.06, 15.37),
        (8.64, 13.52), (10.52, 15.11), (9.95, 15.84), (11.02, 15.60)]
data = np.array(rows)
grids = [(0.0, 20.0, 2001), (5.0, 25.0, 2001)]
n_pred = 5000  # the kernel's CRN sample size in the test
moments = [(10.0, 1.0), (15.0, np.hypot(1.0, 0.5))]


def nr_bandwidth(x):
    return (4.0 / (3.0 * len(x))) ** 0.2 * x.std(ddof=1)


def normal_pdf(y, m, s):
    return np.exp(-0.5 * ((y - m) / s) ** 2) / (s * np.sqrt(2 * np.pi))


nodes = [np.linspace(lo, hi, n) for lo, hi, n in grids]
pred = []
for (m, s), y in zip(moments, nodes):
    h = (4.0 / (3.0 * n_pred)) ** 0.2 * s
    pred.append(normal_pdf(y, m, np.sqrt(s * s + h * h)))


def summed_pr(sample):
    total = 0.0
    for r, y in enumerate(nodes):
        x = sample[:, r]
        h = nr_bandwidth(x)
        f = normal_pdf(y[:, None], x[None, :], h).mean(axis=1)
        total += np.trapz(np.abs(f - pred[r]), y)
    return total


rng = np.random.default_rng(20261129)
B = 200000
sums = np.empty(B)
for b in range(B):
    idx = rng.integers(0, len(rows), len(rows))
    sample = data[idx]
    if np.all(sample[:, 0] == sample[0, 0]):
        sums[b] = np.nan  # no bandwidth: the kernel leaves such a resample out
        continue
    sums[b] = summed_pr(sample)
sums = sums[np.isfinite(sums)]
out = {"rows": rows, "grids": grids, "n": n_pred, "moments": moments, "resamples": int(len(sums)),
       "std": float(sums.std(ddof=1)), "mean": float(sums.mean()), "at_data": summed_pr(data)}
with open(os.path.join(here, "pr_tolerance.json"), "w") as f:
    json.dump(out, f, indent=1)
print(json.dumps({k: out[k] for k in ("resamples", "std", "mean", "at_data")}))
