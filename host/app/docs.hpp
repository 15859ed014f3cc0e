#pragma once
// smi._docs (see docs.cpp): the compiled-in reference texts for stdlib/smi/doc.lua.
#include <lua.hpp>

namespace smi::vm {
/// Adds smi._docs to the smi table on top of the stack. Stack: [smi] -> [smi].
void install_docs(lua_State* L);
}  // namespace smi::vm
