// SPDX-License-Identifier: MIT
#pragma once
// The kernel error family. Kernels throw these with the offending values in the text
// ("need at least 2 points, got 1"); the binding layer prefixes the Lua-visible function name
// and raises a Lua error after the handler (host/luax/luax.hpp, smi::lua::protect).
#include <stdexcept>
#include <string>

namespace smi {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};
/// A caller passed a value outside the domain (empty data, NaN, lower >= upper, ...).
struct InvalidArgument : Error {
  using Error::Error;
};
/// Sizes that must agree do not (Eigen's own asserts vanish under NDEBUG, so we check first).
struct DimensionMismatch : Error {
  using Error::Error;
};
/// An iterative method stopped without meeting its tolerance.
struct NotConverged : Error {
  using Error::Error;
};
/// A long computation was asked to stop (Ctrl-C, timeout).
struct Interrupted : Error {
  using Error::Error;
};

}  // namespace smi
