#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""A NumPy TMCMC (Ching and Chen 2007, with the adaptive COV rule and scaled weighted-covariance
proposals of Betz et al. 2016) on bench/bayes.lua's 10-D Gaussian problem, and the results page.
usage: bayes_peer.py SAMPLES OURS.txt OUT.md"""
import sys
import time

import numpy as np
from scipy import optimize, stats

samples, ours_file, out = int(sys.argv[1]), sys.argv[2], sys.argv[3]
D, PRIOR_SD, Y = 10, 10.0, 25.0
EXACT = D * stats.norm.logpdf(Y, 0.0, np.sqrt(1.0 + PRIOR_SD**2))


def loglik(T):
    return -0.5 * ((T - Y) ** 2).sum(axis=1) - D * 0.5 * np.log(2 * np.pi)


def logprior(T):
    return stats.norm.logpdf(T, 0.0, PRIOR_SD).sum(axis=1)


def tmcmc(n, seed):
    rng = np.random.default_rng(seed)
    x = rng.normal(0.0, PRIOR_SD, (n, D))
    ll = loglik(x)
    beta, logz, stages, evals = 0.0, 0.0, 0, n
    scale = 2.38 / np.sqrt(D)
    while beta < 1.0:
        m = ll.max()

        def cov_gap(db):
            w = np.exp(db * (ll - m))
            return w.std() / w.mean() - 1.0

        db = 1.0 - beta if cov_gap(1.0 - beta) <= 0 else optimize.brentq(cov_gap, 0.0, 1.0 - beta)
        w = np.exp(db * (ll - m))
        logz += np.log(w.mean()) + db * m
        beta = min(1.0, beta + db)
        p = w / w.sum()
        mu = p @ x
        S = ((x - mu).T * p) @ (x - mu)
        L = np.linalg.cholesky(S + 1e-12 * np.eye(D))
        idx = rng.choice(n, n, p=p)
        x, ll = x[idx], ll[idx]
        moved, sweeps = 0.0, 0
        while sweeps < 20 and (sweeps < 2 or moved < 2.0):
            prop = x + scale * rng.normal(size=(n, D)) @ L.T
            llp = loglik(prop)
            evals += n
            acc = np.log(rng.uniform(size=n)) < logprior(prop) + beta * llp - logprior(x) - beta * ll
            x[acc], ll[acc] = prop[acc], llp[acc]
            rate = acc.mean()
            moved += rate
            sweeps += 1
            scale *= np.exp(rate - 0.23)
        stages += 1
    return logz, stages, evals


t0, c0 = time.perf_counter(), time.process_time()
logz, stages, evals = tmcmc(samples, 3)
peer_s, peer_cpu = time.perf_counter() - t0, time.process_time() - c0

ours = {}
for line in open(ours_file):
    k, _, v = line.strip().partition(" ")
    ours[k] = v
f = lambda k: float(ours[k].split()[0])

with open(out, "w") as o:
    o.write("# smi.calibrate_bayes: cost and a NumPy TMCMC peer\n\n")
    o.write(f"Made by `bench/run_bayes.sh` ({samples} particles). Load average before: {ours.get('load_before', '?')}, "
            f"after: {ours.get('load_after', '?')} (a shared 2-core machine: wall times under load are upper bounds).\n\n")
    o.write("## 10-parameter population problem (five unknown inputs, mean and std each; two responses; 9 specimens)\n\n")
    o.write("CPU s: the process's CPU time (both threads); wall s: elapsed, inflated by the machine's load.\n\n")
    o.write("| model | CPU s | wall s | stages | likelihood values | model calls | log Z | its error | log L error (MAP) | converged |\n")
    o.write("|---|---|---|---|---|---|---|---|---|---|\n")
    for case, label in (("kriging", "two Kriging surrogates, 80 points, 5 inputs"), ("lua", "a Lua model (vec arithmetic)")):
        o.write(f"| {label} | {f(case + '_seconds_cpu'):.1f} | {f(case + '_seconds_wall'):.1f} | {ours[case + '_stages']} | {ours[case + '_evaluations']} | "
                f"{ours[case + '_model_runs']} | {f(case + '_log_evidence'):.3f} | {f(case + '_log_evidence_error'):.3f} | "
                f"{f(case + '_loglik_error'):.3f} | {ours[case + '_converged']} |\n")
    o.write("\n## 10-D Gaussian objective (prior N(0, 10^2), likelihood N(25, 1) per parameter; exact log Z "
            f"{EXACT:.4f})\n\n")
    o.write("| sampler | CPU s | wall s | stages | likelihood values | log Z | error vs exact | stated error |\n|---|---|---|---|---|---|---|---|\n")
    o.write(f"| smi.calibrate_bayes (Lua loglik on batches) | {f('gauss_seconds_cpu'):.2f} | {f('gauss_seconds_wall'):.2f} | {ours['gauss_stages']} | "
            f"{ours['gauss_evaluations']} | {f('gauss_log_evidence'):.4f} | {f('gauss_log_evidence') - EXACT:+.4f} | "
            f"{f('gauss_log_evidence_error'):.4f} |\n")
    o.write(f"| NumPy TMCMC (this script; sweeps by moves only) | {peer_cpu:.2f} | {peer_s:.2f} | {stages} | {evals} | {logz:.4f} | {logz - EXACT:+.4f} | - |\n\n")
    o.write(f"CPU time ratio smi.calibrate_bayes / NumPy: {f('gauss_seconds_cpu') / peer_cpu:.2f}, for "
            f"{int(ours['gauss_evaluations']) / evals:.1f} times the likelihood values (its sweeps also run until the chains "
            "forget their seeds). The wall ratio includes smi-lua's start.\n")
print(open(out).read())
