#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference values for smi.mat's linear algebra (tests/lua/test_mat_linalg.lua): solve, inverse,
det and Cholesky by scipy.linalg, and the symmetric and generalised symmetric eigenproblems by
scipy.linalg.eigh (LAPACK syevr/sygvd), on a 5x5 system and a spring-mass chain.
Run: /usr/bin/python3 tests/reference/linalg_scipy.py   Output: linalg_scipy.json (matrices
by rows; eigenvectors by column as in smi.mat.eigh, each with its largest entry made positive,
the sign rule smi.mat.eigh documents)."""
import json, os
import numpy as np
from scipy import linalg

rng = np.random.default_rng(20261126)
A = rng.normal(size=(5, 5)) + 5 * np.eye(5)           # well conditioned, not symmetric
b = rng.normal(size=5)
B = rng.normal(size=(5, 2))
G = rng.normal(size=(5, 5))
S = G @ G.T + 5 * np.eye(5)                            # symmetric positive definite

# Spring-mass chain: 4 masses, 5 springs (both ends fixed), N/mm and t.
k = np.array([1200.0, 800.0, 1500.0, 900.0, 1100.0])
m = np.array([2.0e-3, 1.5e-3, 3.0e-3, 1.0e-3])
K = np.zeros((4, 4))
for i in range(4):
    K[i, i] = k[i] + k[i + 1]
    if i + 1 < 4:
        K[i, i + 1] = K[i + 1, i] = -k[i + 1]
M = np.diag(m)
M[0, 1] = M[1, 0] = 0.2e-3                             # a consistent-mass coupling: M not diagonal


def signed(V):
    V = V.copy()
    for j in range(V.shape[1]):
        i = int(np.argmax(np.abs(V[:, j])))
        if V[i, j] < 0:
            V[:, j] *= -1
    return V


w_s, V_s = linalg.eigh(S)
w_g, V_g = linalg.eigh(K, M)
out = {
    "A": A.tolist(), "b": b.tolist(), "B": B.tolist(), "S": S.tolist(), "K": K.tolist(), "M": M.tolist(),
    "solve_b": linalg.solve(A, b).tolist(), "solve_B": linalg.solve(A, B).tolist(),
    "inverse": linalg.inv(A).tolist(), "det": float(linalg.det(A)),
    "chol": linalg.cholesky(S, lower=True).tolist(),
    "eigh_values": w_s.tolist(), "eigh_vectors": signed(V_s).tolist(),
    "geigh_values": w_g.tolist(), "geigh_vectors": signed(V_g).tolist(),
}
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "linalg_scipy.json"), "w") as f:
    json.dump(out, f, indent=1)
    f.write("\n")
