// SPDX-License-Identifier: MIT
#pragma once
// Small argument helpers shared by the stats bindings.
#include <Eigen/Core>
#include <lua.hpp>
#include <string>

#include "luax/luax.hpp"

namespace smi::bind::stats {

/// A required numeric option read by a schema as NaN when absent; throws naming it and the call.
double required(double v, const char* key, const char* fname);
/// The data argument at idx (vec or table), checked finite (naming the index) and non-empty.
Eigen::VectorXd data_arg(lua_State* L, int idx, const char* fname, Eigen::Index min_size = 1);
/// Pushes {x = vec, pdf = vec, cdf = vec} (pdf omitted when has_pdf is false).
void push_curve(lua_State* L, const Eigen::VectorXd& x, const Eigen::VectorXd* pdf, const Eigen::VectorXd* cdf);

}  // namespace smi::bind::stats
