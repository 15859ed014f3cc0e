// SPDX-License-Identifier: MIT
#pragma once
// The read-eval-print loop (lua.c's doREPL over the runtime's sandboxed state): try the line
// as an expression first ("return <line>"), keep reading while the chunk is incomplete (the
// parser stops at <eof>), print the results with the bounded printer.
#include "app/runtime.hpp"

namespace smi::repl {

/// Runs until end of input (Ctrl-D) or os.exit; returns the exit status (0, or os.exit's code).
int run(app::Runtime& rt);

/// True if a load status/message means "the chunk is not finished yet" (lua.c's incomplete()).
bool incomplete(lua_State* L, int status);

}  // namespace smi::repl
