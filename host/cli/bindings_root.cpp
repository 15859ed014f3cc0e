// SPDX-License-Identifier: MIT
#include "cli/bindings_root.hpp"

#include "bindings/doc.hpp"
#include "bindings/modules.hpp"

namespace smi::cli {

app::Bindings all_bindings() { return {luaopen_smi, bind::binding_docs}; }

}  // namespace smi::cli
