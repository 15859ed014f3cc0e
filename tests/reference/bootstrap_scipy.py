#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference percentile bootstrap intervals of a mean from SciPy (scipy.stats.bootstrap,
method="percentile"), for tests/kernels/improve/test_bootstrap_reference.cpp:
  * the 95 % interval from 200000 resamples (its endpoints' Monte Carlo error is negligible);
  * for 50 and 400 resamples, the spread (standard deviation) of each endpoint over 400
    independent bootstraps: the Monte Carlo error a single bootstrap of that size has.
Output: bootstrap_scipy.json. Run with Debian's /usr/bin/python3 (python3-scipy)."""
import json, os
import numpy as np
from scipy import stats

here = os.path.dirname(os.path.abspath(__file__))
# 20 skewed data (a lognormal-like sample written out, so the C++ test holds the same numbers)
x = [0.61, 0.72, 0.80, 0.85, 0.91, 0.95, 1.02, 1.05, 1.11, 1.18,
     1.22, 1.30, 1.37, 1.45, 1.58, 1.71, 1.90, 2.20, 2.65, 3.40]
data = (np.array(x),)


def interval(n, seed):
    r = stats.bootstrap(data, np.mean, n_resamples=n, confidence_level=0.95, method="percentile",
                        random_state=np.random.default_rng(seed))
    return r.confidence_interval.low, r.confidence_interval.high


out = {"data": x, "level": 0.95, "reference": dict(zip(("lower", "upper"), interval(200000, 1)))}
for n in (50, 400):
    ends = np.array([interval(n, 1000 + s) for s in range(400)])
    out["spread_%d" % n] = {"lower_sd": float(ends[:, 0].std(ddof=1)), "upper_sd": float(ends[:, 1].std(ddof=1)),
                            "lower_mean": float(ends[:, 0].mean()), "upper_mean": float(ends[:, 1].mean()), "runs": 400}
with open(os.path.join(here, "bootstrap_scipy.json"), "w") as f:
    json.dump(out, f, indent=2, sort_keys=True)
    f.write("\n")
