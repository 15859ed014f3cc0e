# SPDX-License-Identifier: MIT
"""The Gaussian KDE the SciPy peers of the calibration benchmarks use (normal-reference bandwidth,
dense sums in NumPy): one copy for calibrate_peers.py and calibrate_hidden_peers.py."""
import numpy as np
import scipy.special

SQ2PI = np.sqrt(2 * np.pi)


def normal_reference(x):
    return (4.0 / (3.0 * len(x))) ** 0.2 * x.std(ddof=1)


def kde_pdf(sample, h, x):
    return np.exp(-0.5 * ((x[:, None] - sample[None, :]) / h) ** 2).sum(axis=1) / (len(sample) * h * SQ2PI)


def kde_cdf(sample, h, x):
    return scipy.special.ndtr((x[:, None] - sample[None, :]) / h).mean(axis=1)
