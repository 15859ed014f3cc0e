#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference for smi::kriging at fixed hyperparameters: OpenTURNS 1.20 KrigingAlgorithm on
DACE-normalised data (spec §4 mapping: SquaredExponential scale s = 1/sqrt(2 theta), amplitude 1,
parameters not optimised), for a 3-input design with constant, linear and quadratic bases.
Writes kriging_openturns.csv: case, theta1..3, then per test point x1..x3, OT mean and OT
conditional variance, both in normalised units (mean*sY + mY gives the response; with amplitude 1
the variance equals DACE's mse / sigma2)."""
import numpy as np
import openturns as ot

rng = np.random.default_rng(4)
S = rng.uniform(0, 1, (25, 3)) * [1.0, 2.0, 0.5] + [0.0, -1.0, 3.0]
Y = np.sin(3 * S[:, 0]) + S[:, 1] ** 2 + np.exp(S[:, 2] - 3) * S[:, 0]
T = rng.uniform(0, 1, (6, 3)) * [1.0, 2.0, 0.5] + [0.0, -1.0, 3.0]
mS, sS = S.mean(0), S.std(0, ddof=1)
mY, sY = Y.mean(), Y.std(ddof=1)
Sn, Yn, Tn = (S - mS) / sS, (Y - mY) / sY, (T - mS) / sS
theta = np.array([0.7, 0.25, 1.6])

out = open(__file__.replace(".py", ".csv"), "w")
out.write("# design (25 rows x1,x2,x3,y) then per case: basis, theta, test rows x1,x2,x3,mean_norm,var_norm\n")
for s, y in zip(S, Y):
    out.write("design,%.17g,%.17g,%.17g,%.17g\n" % (*s, y))
for name, fac in (("constant", ot.ConstantBasisFactory), ("linear", ot.LinearBasisFactory),
                  ("quadratic", ot.QuadraticBasisFactory)):
    cov = ot.SquaredExponential(list(1 / np.sqrt(2 * theta)), [1.0])
    algo = ot.KrigingAlgorithm(ot.Sample(Sn), ot.Sample(Yn[:, None]), cov, fac(3).build())
    algo.setOptimizeParameters(False)
    algo.run()
    res = algo.getResult()
    mean = np.asarray(res.getConditionalMean(ot.Sample(Tn))).ravel()
    var = np.array([res.getConditionalCovariance(ot.Point(t))[0, 0] for t in Tn])
    for x, m, v in zip(T, mean, var):
        out.write("%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n" % (name, *theta, *x, m, v))
