#pragma once
// Reference texts of the C++ bindings. Each binding folder keeps its texts in a *_doc.cpp file
// beside the registration (format: stdlib/smi/doc.lua's header) and exposes them through one
// function listed in doc_sources.cpp. Defaults come from the kernels' option structs through
// ${name} placeholders filled by fill(), so a changed default changes the reference.
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace smi::bind {

struct DocText {
  const char* source;  // the file that holds the text, e.g. "bindings/stats/kde_doc.cpp"
  std::string text;    // one or more "@ name(...)" blocks
};

/// Replaces every ${key} in text with its value; throws smi::Error on a ${key} not given, so a
/// misspelt placeholder fails the doc tests instead of printing "${...}".
std::string fill(std::string_view text, std::initializer_list<std::pair<std::string_view, std::string>> values);
/// A default value as the reference shows it: %.10g (0.95, 1e-06, 200).
std::string num(double v);

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
