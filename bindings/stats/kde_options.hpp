// SPDX-License-Identifier: MIT
#pragma once
// The option schemas of smi.kde, smi.kde_bd and smi.kde_ebd (luax/option_schema.hpp): the
// binding reads its options through them and kde_doc.cpp lists them from them.
#include <Eigen/Core>

#include <limits>
#include <string>

#include "kernels/stats/kde.hpp"
#include "kernels/stats/kde_bounded.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::stats {

/// smi.kde's options: the kernel's, plus the bandwidth (a number or a rule name, read by hand).
using KdeArgs = smi::stats::KdeOptions;

/// smi.kde_bd's options: the bounds (required: NaN until given) and the loop's options.
struct KdeBdArgs : smi::stats::BoundedKdeOptions {
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
};

/// smi.kde_ebd's options: the bound estimation's and the loop's.
struct KdeEbdArgs : smi::stats::BoundedKdeOptions, smi::stats::EbdBoundsOptions {};

const lua::Schema<KdeArgs>& kde_schema();
const lua::Schema<KdeBdArgs>& kde_bd_schema();
const lua::Schema<KdeEbdArgs>& kde_ebd_schema();

}  // namespace smi::bind::stats
