// SPDX-License-Identifier: MIT
#pragma once
// Reference texts compiled into the binary (format: stdlib/smi/doc.lua's header). The bindings
// keep theirs in *_doc.cpp files; the app adds the host functions'. Defaults come from the option
// structs through ${name} placeholders filled by fill(), so a changed default changes the reference.
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace smi::lua {

struct DocText {
  const char* source;  // the file that holds the text, e.g. "bindings/stats/kde_doc.cpp"
  std::string text;    // one or more "@ name(...)" blocks
};

/// Replaces every ${key} in text with its value; throws smi::Error on a ${key} not given, so a
/// misspelt placeholder fails the doc tests instead of printing "${...}".
std::string fill(std::string_view text, std::initializer_list<std::pair<std::string_view, std::string>> values);
/// A default value as the reference shows it: %.10g (0.95, 1e-06, 200).
std::string num(double v);

}  // namespace smi::lua
