// SPDX-License-Identifier: MIT
#pragma once
// The run's RunContext (core/run_context.hpp) as the bindings reach it: stored in the Lua
// registry next to the Policy by the runtime, read through run_context(L). Also the two ways a
// binding acts on it: warn() (the run's one warning channel) and stop_run() (os.exit and
// --dry-run end the run through the cancellation token, with reason exit).
#include <string_view>
#include <lua.hpp>

#include "platform/core/cancel.hpp"
#include "platform/core/run_context.hpp"

namespace smi::lua {

/// The run context of this state (installed by the runtime). A state without one gets a default
/// (seed kDefaultSeed, quiet, no token: nothing stops), which only kernel-level tests use.
RunContext& run_context(lua_State* L);
/// Stores `ctx` (not owned; must outlive the state) in the registry.
void set_run_context(lua_State* L, RunContext* ctx);

/// The run's cancellation token, for a kernel's `stop` argument (one no one sets outside a run).
const cancel::Token& cancel_token(lua_State* L);

/// Warns through the run's sink: collected for smi.warnings(), printed unless the run is quiet.
void warn(lua_State* L, std::string_view source, std::string_view text);

/// Sets the run's token (first reason wins) and arms the state's instruction hook to fire at
/// the next instruction, so the hook (vm/limits) acts on it at once: os.exit, --dry-run.
void stop_run(lua_State* L, cancel::Reason why, int detail = 0);
/// Arms the installed hook to fire at the next instruction (a bound function that met the
/// token's stop, so a pcall around it cannot run on for thousands of instructions).
void check_stop_now(lua_State* L);

}  // namespace smi::lua
