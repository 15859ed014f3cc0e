// SPDX-License-Identifier: MIT
#pragma once
// Reference texts of the C++ bindings. Each binding folder keeps its texts in a *_doc.cpp file
// beside the registration (format: stdlib/smi/doc.lua's header) and exposes them through one
// function listed in doc_sources.cpp (DocText and fill: luax/doc_text.hpp).
#include <vector>

#include "luax/doc_text.hpp"

namespace smi::bind {

using lua::DocText;
using lua::fill;
using lua::num;

/// Every binding area's texts, in a fixed order.
std::vector<DocText> binding_docs();

// One per binding folder (in *_doc.cpp beside the registration).
DocText doc_vec();
DocText doc_mat();
DocText doc_rng();
DocText doc_csv_json();
DocText doc_stats_dist();
DocText doc_stats_kde();
DocText doc_stats_metric();
DocText doc_surrogate();
DocText doc_eval();
DocText doc_improve();

}  // namespace smi::bind
