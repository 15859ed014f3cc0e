#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Maximum-likelihood fits by SciPy 1.10 for tests/kernels/stats/test_fit.cpp.
Data: spec §8.1 (9 points) and 30 gamma-distributed measurements (seeded).
Output: stats_fit.csv with rows  dataset,family,param1,param2,loglik
(weibull/gamma/lognormal with loc fixed at 0, as smi fits them)."""
import numpy as np
from scipy import stats

X = np.array([30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20])
Y = np.round(stats.gamma(a=4.0, scale=2.5).rvs(size=30, random_state=np.random.default_rng(7)), 4)
rows = []
for name, d in (("x9", X), ("y30", Y)):
    m, s = stats.norm.fit(d)
    rows.append((name, "normal", m, s, stats.norm(m, s).logpdf(d).sum()))
    sl, _, sc = stats.lognorm.fit(d, floc=0)
    rows.append((name, "lognormal", np.log(sc), sl, stats.lognorm(sl, 0, sc).logpdf(d).sum()))
    k, _, lam = stats.weibull_min.fit(d, floc=0)
    rows.append((name, "weibull", k, lam, stats.weibull_min(k, 0, lam).logpdf(d).sum()))
    loc, sc = stats.gumbel_r.fit(d)
    rows.append((name, "gumbel", loc, sc, stats.gumbel_r(loc, sc).logpdf(d).sum()))
    a, _, sc = stats.gamma.fit(d, floc=0)
    rows.append((name, "gamma", a, sc, stats.gamma(a, 0, sc).logpdf(d).sum()))
with open(__file__.replace(".py", ".csv"), "w") as f:
    f.write("# " + " ".join(f"{v:.4f}" for v in Y) + "\n")
    for r in rows:
        f.write(",".join([r[0], r[1]] + [f"{v:.12g}" for v in r[2:]]) + "\n")
