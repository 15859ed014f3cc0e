// SPDX-License-Identifier: MIT
#pragma once
// The program's composition root: the one place that knows both the runtime (app) and the Lua
// face of the kernels (bindings). Everything that makes a Runtime takes its bindings from here.
#include "app/runtime.hpp"

namespace smi::cli {

/// luaopen_smi and the bindings' reference texts, for app::Runtime.
app::Bindings all_bindings();

}  // namespace smi::cli
