// SPDX-License-Identifier: MIT
#pragma once
// C++ heap held by Lua objects (vec, mat, Kriging) counted against --max-memory and reported to
// Lua's collector. Lua's allocator sees only the small userdata of a box; without this a script
// held 4 GB of vecs under --max-memory 64, and garbage vecs never made the collector run.
#include <cstddef>
#include <lua.hpp>

namespace smi::lua {

/// The run's budget (owned by the runtime; the allocator reads `external` too).
struct MemoryBudget {
  std::size_t limit = 0;                  // bytes; 0 = no limit
  const std::size_t* lua_used = nullptr;  // bytes of Lua heap in use
  std::size_t external = 0;               // bytes held by boxes
  std::size_t since_step = 0;             // external bytes added since the last collector step
};

/// Stores `b` (not owned) in the registry. Without one, nothing is counted.
void set_memory_budget(lua_State* L, MemoryBudget* b);

/// Raises a Lua error naming `what` when `count` values of `elem_bytes` each cannot be held:
/// beyond --max-memory (after a full collection) or beyond any size this machine can allocate.
/// Call it before allocating a size a script chose (smi.vec(n), smi.mat(r, c)).
void check_alloc(lua_State* L, double count, std::size_t elem_bytes, const char* what);

/// The same check for code inside protect(): throws smi::Error with the same message. Every
/// binding that allocates a size a script chose calls one of them before allocating (pushing
/// the result counts it only once it exists, too late for a 1 GB sample).
void require_room(lua_State* L, double count, std::size_t elem_bytes, const char* what);

}  // namespace smi::lua
