#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference for smi::doe::sobol: SciPy 1.10's unscrambled Sobol' sequence (Joe & Kuo
direction numbers), points 1..511 (point 0, all zeros, is skipped as smi.doe.sobol does),
37 dimensions. These points are multiples of 2^-9; the CSV stores x * 512 as integers."""
import numpy as np
from scipy.stats import qmc

x = qmc.Sobol(d=37, scramble=False).random(512)[1:]
np.savetxt(__file__.replace(".py", ".csv"), np.rint(x * 512).astype(int), delimiter=",", fmt="%d")
