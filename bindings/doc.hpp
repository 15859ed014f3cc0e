// SPDX-License-Identifier: MIT
#pragma once
// Reference texts of the C++ bindings. Each binding folder keeps its texts in a *_doc.cpp file
// beside the registration (format: stdlib/smi/doc.lua's header) and exposes them through one
// function named in the area's record in areas.cpp (DocText and fill: luax/doc_text.hpp).
#include <vector>

#include "bindings/modules.hpp"
#include "luax/doc_text.hpp"

namespace smi::bind {

using lua::DocText;
using lua::fill;
using lua::num;

/// Every binding area's texts, in a fixed order.
std::vector<DocText> binding_docs();

// The texts of each area: declared with its open function in modules.hpp.

}  // namespace smi::bind
