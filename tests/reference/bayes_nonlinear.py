#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference posteriors and evidences for tests/lua/test_calibrate_bayes.lua, by quadrature
(NumPy 1.24), independent of the sampler.

1. banana: uniform priors a in [-3, 3], b in [-2, 4];
   log L = -0.5 ((a - 0.5)^2 / 0.3^2 + (b - a^2)^2 / 0.2^2) (unnormalised).
   log Z, posterior means and sds on a 1201 x 1201 grid (Simpson's rule).
2. population: one unknown input x1 ~ normal(mu, sigma) (mu, sigma calibrated), a known input
   x2 ~ normal(0, 0.2); responses y1 = x1 + 0.2 x1^2 + x2, y2 = exp(0.3 x1) - x2 (correlated
   through x1 and x2), noise sd 0.1 on each; 6 specimens drawn at mu = 1.1, sigma = 0.3 (seeded).
   Priors: mu normal(1.0, 0.3) truncated to [0, 2.5]; sigma uniform on [0.05, 0.8].
   p(y_i | mu, sigma) = int int N(y_i; f(x), 0.1^2 I) N(x1; mu, sigma) N(x2; 0, 0.2) by
   Gauss-Hermite (40 x 40 nodes); log Z and posterior moments on a 161 x 161 grid (Simpson).
Output: bayes_nonlinear.json."""
import json

import numpy as np
from scipy import integrate, stats


def simpson2(f, x, y):
    return integrate.simpson(integrate.simpson(f, x=y, axis=1), x=x)


def moments(logf, x, y):
    m = logf.max()
    f = np.exp(logf - m)
    z = simpson2(f, x, y)
    X, Y = np.meshgrid(x, y, indexing="ij")
    out = {"log_evidence": float(np.log(z) + m)}
    for name, V in (("a", X), ("b", Y)):
        mean = simpson2(f * V, x, y) / z
        var = simpson2(f * (V - mean) ** 2, x, y) / z
        out[name] = {"mean": float(mean), "std": float(np.sqrt(var))}
    return out


def banana():
    a = np.linspace(-3, 3, 1201)
    b = np.linspace(-2, 4, 1201)
    A, B = np.meshgrid(a, b, indexing="ij")
    loglik = -0.5 * ((A - 0.5) ** 2 / 0.3**2 + (B - A**2) ** 2 / 0.2**2)
    r = moments(loglik - np.log(6.0 * 6.0), a, b)
    return {"log_evidence": r["log_evidence"], "mean": {"a": r["a"]["mean"], "b": r["b"]["mean"]},
            "std": {"a": r["a"]["std"], "b": r["b"]["std"]}}


def population():
    rng = np.random.default_rng(11)
    n = 6
    x1 = rng.normal(1.1, 0.3, n)
    x2 = rng.normal(0.0, 0.2, n)
    y = np.column_stack([x1 + 0.2 * x1**2 + x2, np.exp(0.3 * x1) - x2]) + rng.normal(0, 0.1, (n, 2))
    y = np.round(y, 6)
    t, w = np.polynomial.hermite_e.hermegauss(40)
    w = w / np.sqrt(2 * np.pi)
    mu = np.linspace(0.0, 2.5, 161)
    sg = np.linspace(0.05, 0.8, 161)
    z2 = 0.2 * t
    loglik = np.zeros((mu.size, sg.size))
    for i, m in enumerate(mu):
        # x1 nodes for every sigma: (sg, 60)
        X1 = m + sg[:, None] * t[None, :]
        f1 = X1[:, :, None] + 0.2 * X1[:, :, None] ** 2 + z2[None, None, :]
        f2 = np.exp(0.3 * X1[:, :, None]) - z2[None, None, :]
        W = w[None, :, None] * w[None, None, :]
        for k in range(n):
            dens = np.exp(-0.5 * (((y[k, 0] - f1) / 0.1) ** 2 + ((y[k, 1] - f2) / 0.1) ** 2)) / (2 * np.pi * 0.01)
            loglik[i] += np.log((dens * W).sum(axis=(1, 2)))
    prior_mu = stats.norm.logpdf(mu, 1.0, 0.3) - np.log(stats.norm.cdf(2.5, 1.0, 0.3) - stats.norm.cdf(0.0, 1.0, 0.3))
    logpost = loglik + prior_mu[:, None] - np.log(0.8 - 0.05)
    r = moments(logpost, mu, sg)
    return {"data": {"y1": y[:, 0].tolist(), "y2": y[:, 1].tolist()}, "log_evidence": r["log_evidence"],
            "mean": {"x1.mean": r["a"]["mean"], "x1.std": r["b"]["mean"]},
            "std": {"x1.mean": r["a"]["std"], "x1.std": r["b"]["std"]}}


out = {"banana": banana(), "population": population()}
with open(__file__.replace(".py", ".json"), "w") as f:
    json.dump(out, f, indent=1)
    f.write("\n")
