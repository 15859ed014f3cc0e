// SPDX-License-Identifier: MIT
#pragma once
// Bandwidth rules for the 1-D Gaussian kernel, named by formula (spec §1.1). Every rule throws
// InvalidArgument for fewer than 2 points or zero spread (a KDE of ties is a point mass: pass a
// bandwidth explicitly instead).
#include <string>
#include <string_view>
#include <vector>

#include "platform/core/descriptive.hpp"

namespace smi::stats {

/// Normal reference ("silverman", default): h = (4/(3n))^{1/5} sd = 1.05922 sd n^{-1/5}.
double bandwidth_normal_reference(ConstVec x);
/// The rounded constant: h = 1.06 sd n^{-1/5} (Scott 1992's 1-D normal reference).
double bandwidth_normal_106(ConstVec x);
/// Silverman's robust rule of thumb: 0.9 min(sd, IQR/1.34) n^{-1/5}; IQR type 7; IQR = 0 -> sd.
double bandwidth_robust(ConstVec x);
/// scipy's "scott": h = sd n^{-1/5}.
double bandwidth_scott(ConstVec x);
/// MATLAB ksdensity: (MAD/0.6745) (4/(3n))^{1/5}; MAD = 0 -> range; range = 0 -> 1.
double bandwidth_mad(ConstVec x);
/// Least-squares (unbiased) cross-validation: minimises
/// LSCV(h) = ∫f̂² − 2/n Σ f̂_{-i}(x_i) (closed form for the Gaussian kernel) by golden section
/// on log h over [0.05, 2] x normal reference, after a coarse scan (LSCV has local minima).
double bandwidth_lscv(ConstVec x);
/// Sheather–Jones solve-the-equation plug-in (1991) with Gaussian-kernel functional estimates
/// and normal-reference pilots for the 6th and 8th derivative functionals.
double bandwidth_sheather_jones(ConstVec x);

/// Bandwidth by rule name: "silverman" | "normal_reference" | "normal" (all the 1.05922 rule),
/// "1.06", "robust" | "silverman_robust", "scott", "mad" | "matlab", "lscv" | "ucv" | "cv",
/// "sj" | "sheather_jones". Throws InvalidArgument listing the names for anything else.
double bandwidth_by_name(ConstVec x, std::string_view rule);
/// The rule names accepted by bandwidth_by_name (for error messages and docs).
const std::vector<std::string>& bandwidth_rule_names();

}  // namespace smi::stats
