#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Peer for bench/calibrate_hidden.lua: SciPy's SLSQP with its default 2-point
differences (k + 1 = 11 model passes a gradient for the 10 parameters) on the same PR objective
as smi's -- the same CRN sample (recovered from the start's inputs x0.txt), data, grids, bounds,
start and scaling to [0, 1] -- timed in the same run; merges the Lua bench's output and writes
bench/results/calibrate_hidden.md.
usage: calibrate_hidden_peers.py <dir> <ours.txt> <results.md>"""
import sys, time, datetime
import numpy as np
import scipy, scipy.optimize, scipy.special
from peer_kde import normal_reference, kde_pdf, kde_cdf

d, ours_path, out = sys.argv[1], sys.argv[2], sys.argv[3]
ours = {}
for line in open(ours_path):
    k, *v = line.split()
    ours[k] = v

# tests/lua/hidden_problem.lua's box: (lower, upper, start) for x1..x5 mean, std
BOX = np.array([[8, 12, 9], [0.2, 2, 1.2], [1.5, 3, 2.6], [0.05, 0.6, 0.2], [3, 7, 4], [0.1, 1.5, 0.8],
                [-1, 1, 0.4], [0.1, 1, 0.3], [0.6, 1.6, 1.3], [0.05, 0.5, 0.3]], dtype=float)
LO, HI, START = BOX[:, 0], BOX[:, 1], BOX[:, 2]
FAMILIES = ["normal", "lognormal", "uniform", "normal", "lognormal"]


def lognormal(m, s):
    v = np.log1p((s / m) ** 2)
    return np.log(m) - 0.5 * v, np.sqrt(v)


def to_z(x, fam, m, s):
    if fam == "normal": return (x - m) / s
    if fam == "lognormal":
        mu, sig = lognormal(m, s)
        return (np.log(x) - mu) / sig
    a, b = m - np.sqrt(3) * s, m + np.sqrt(3) * s
    return scipy.special.ndtri((x - a) / (b - a))


def from_z(z, fam, m, s):
    if fam == "normal": return m + s * z
    if fam == "lognormal":
        mu, sig = lognormal(m, s)
        return np.exp(mu + sig * z)
    a, b = m - np.sqrt(3) * s, m + np.sqrt(3) * s
    return a + (b - a) * scipy.special.ndtr(z)


def model(X):
    x1, x2, x3, x4, x5 = X.T
    return [x1 * x2 + x3, x3 * np.exp(0.2 * x4) + 2 * x5 ** 2, x1 / x5 + x2 * x4 + 0.2 * x3 ** 2]



X0 = np.loadtxt(f"{d}/x0.txt")
Z = np.column_stack([to_z(X0[:, j], FAMILIES[j], START[2 * j], START[2 * j + 1]) for j in range(5)])
data = [np.array(r) for r in np.loadtxt(f"{d}/data.txt")]
grids = np.loadtxt(f"{d}/grids.txt")
nodes, fexp, exp_out = [], [], []
for j in range(3):
    g = np.linspace(grids[j, 0], grids[j, 1], int(grids[j, 2]))
    hd = normal_reference(data[j])
    nodes.append(g)
    fexp.append(kde_pdf(data[j], hd, g))
    F = kde_cdf(data[j], hd, np.array([g[0], g[-1]]))
    exp_out.append(max(0.0, F[0]) + max(0.0, 1 - F[1]))
nfev = 0


def objective(u):
    global nfev
    nfev += 1
    t = LO + np.clip(u, 0, 1) * (HI - LO)
    X = np.column_stack([from_z(Z[:, j], FAMILIES[j], t[2 * j], t[2 * j + 1]) for j in range(5)])
    total = 0.0
    for j, y in enumerate(model(X)):
        h = normal_reference(y)
        g = nodes[j]
        diff = np.abs(fexp[j] - kde_pdf(y, h, g))
        step = (g[-1] - g[0]) / (len(g) - 1)
        F = kde_cdf(y, h, np.array([g[0], g[-1]]))
        total += step * (diff.sum() - 0.5 * (diff[0] + diff[-1])) + max(0.0, F[0]) + max(0.0, 1 - F[1]) + exp_out[j]
    return total


u0 = (START - LO) / (HI - LO)
# The same objective: SciPy's value at smi's optimum against smi's.
th_ours = np.array([float(v) for v in ours["model_forward_theta"]])
check = objective((th_ours - LO) / (HI - LO))
nfev = 0
c0, t0 = time.process_time(), time.perf_counter()
res = scipy.optimize.minimize(objective, u0, method="SLSQP", bounds=[(0, 1)] * 10)  # defaults: ftol 1e-6, 2-point differences
cpu, wall, n_scipy = time.process_time() - c0, time.perf_counter() - t0, nfev
th_scipy = LO + res.x * (HI - LO)


def dist(th):
    return np.max(np.abs(th - th_scipy) / (HI - LO))


L = [f"# The hidden-style calibration: smi vs SciPy SLSQP, {datetime.date.today()}", "",
     "Ten parameters (means and stds of five inputs: normal, lognormal, uniform, normal, lognormal), three responses of a",
     "smooth nonlinear Lua function model WITHOUT a gradient, nine measurements each, PR on 4001-node grids, n = 2000 CRN",
     "samples (tests/lua/hidden_problem.lua). smi runs through smi-lua (the model is the Lua function); SciPy 2-point",
     "differences on the same objective in NumPy (the same CRN sample, data, grids, box and start, scaled to [0, 1]).",
     f"Made by bench/run_calibrate_hidden.sh; load average {ours.get('load', ['?'])[0]}; SciPy {scipy.__version__}.", "",
     f"Same objective: SciPy's value at smi's optimum {check:.10f}, smi's {float(ours['model_forward_objective'][0]):.10f}.", "",
     "| run | objective | evaluations | model passes (n rows each) | CPU | max distance to SciPy's optimum (of each range) | status |",
     "|---|---|---|---|---|---|---|"]
rows = {}
for key, name in (("model_forward", "smi, model differences (forward, k + 1 = 6 passes a gradient, 5 where the value is known), default tolerances"),
                  ("model_central", "smi, model differences (central, 2k + 1 = 11 passes)"),
                  ("objective_differences", "smi, objective differences (gradient = \"differences\", 2k' + 1 = 21), maxeval 500")):
    th = np.array([float(v) for v in ours[key + "_theta"]])
    r = dict(obj=float(ours[key + "_objective"][0]), ev=int(ours[key + "_evaluations"][0]), passes=int(ours[key + "_model_passes"][0]),
             cpu=float(ours[key + "_cpu"][0]), st=ours[key + "_status"][0], dist=dist(th))
    rows[key] = r
    L.append(f"| {name} | {r['obj']:.6f} | {r['ev']} | {r['passes']} | {r['cpu']:.2f} s | {r['dist']:.1e} | {r['st']} |")
L.append(f"| SciPy SLSQP, 2-point differences (default ftol 1e-6) | {res.fun:.6f} | {n_scipy} | {n_scipy} | {cpu:.2f} s | 0 | {res.message} |")
f = rows["model_forward"]
# smi's forward run: a gradient is one model call of k = 5 blocks (its value known) or 6, a value one call of
# one block, so passes - calls = 4 per gradient (at most: a gradient with its own base block adds one more)
runs = int(ours["model_forward_model_runs"][0])
grads = (f["passes"] - runs) // 4
L += ["", f"- model passes: SciPy {n_scipy} / smi {f['passes']} = **{n_scipy / f['passes']:.2f}x** fewer for smi (target >= 1.5x)",
      f"- iterations: SciPy {res.nit} ({res.njev} gradients of 10 extra passes each, {n_scipy - 10 * res.njev} values); "
      f"smi about {grads} gradients (5 passes each where the value was just computed) and {runs - grads} values "
      f"(model calls {runs}, passes {f['passes']})",
      f"- CPU: SciPy {cpu:.2f} s / smi {f['cpu']:.2f} s = **{cpu / f['cpu']:.2f}x** less for smi (target >= 3x)",
      f"- optimum: the largest parameter difference is {f['dist']:.1e} of its range (target <= 1e-3)", ""]
open(out, "w").write("\n".join(L) + "\n")
print("\n".join(L))
