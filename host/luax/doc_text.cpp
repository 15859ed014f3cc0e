// SPDX-License-Identifier: MIT
// The placeholder filler of the reference texts (see doc_text.hpp).
#include "luax/doc_text.hpp"

#include <fmt/format.h>

#include "platform/core/errors.hpp"

namespace smi::lua {

std::string fill(std::string_view text, std::initializer_list<std::pair<std::string_view, std::string>> values) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t at = text.find("${", i);
    if (at == std::string_view::npos) {
      out.append(text.substr(i));
      break;
    }
    out.append(text.substr(i, at - i));
    const std::size_t end = text.find('}', at);
    if (end == std::string_view::npos) throw Error("doc text: unclosed ${ placeholder");
    const std::string_view key = text.substr(at + 2, end - at - 2);
    bool found = false;
    for (const auto& [k, v] : values)
      if (k == key) {
        out.append(v);
        found = true;
        break;
      }
    if (!found) throw Error(fmt::format("doc text: no value for placeholder ${{{}}}", key));
    i = end + 1;
  }
  return out;
}

std::string num(double v) { return fmt::format("{:.10g}", v); }

}  // namespace smi::lua
