// SPDX-License-Identifier: MIT
#pragma once
// smi._docs (see docs.cpp): the compiled-in reference texts for stdlib/smi/doc.lua.
#include <string>
#include <vector>
#include <lua.hpp>

#include "luax/doc_text.hpp"

namespace smi::app {
/// Adds smi._docs to the smi table on top of the stack: the texts `binding_docs` returns and
/// the host functions'. Stack: [smi] -> [smi].
void install_docs(lua_State* L, std::vector<lua::DocText> (*binding_docs)());
}  // namespace smi::app
