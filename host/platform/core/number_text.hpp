// SPDX-License-Identifier: MIT
#pragma once
// The shortest decimal text of a double that reads back to the same bits ("0.1", "1e+300"): how
// the JSON and CSV writers put numbers in files that must read back exactly.
#include <charconv>
#include <string>

namespace smi {

inline std::string number_text(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace smi
