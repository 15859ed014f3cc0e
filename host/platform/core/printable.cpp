// SPDX-License-Identifier: MIT
#include "platform/core/printable.hpp"

#include <cstdio>

namespace smi {

std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  char esc[16];
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      std::snprintf(esc, sizeof esc, "\\x%02X", c);
      out += esc;
    } else if (c == 0xC2 && i + 1 < s.size() && static_cast<unsigned char>(s[i + 1]) >= 0x80 &&
               static_cast<unsigned char>(s[i + 1]) <= 0x9F) {
      std::snprintf(esc, sizeof esc, "\\u{%02X}", static_cast<unsigned char>(s[i + 1]));
      out += esc;
      ++i;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

}  // namespace smi
