// SPDX-License-Identifier: MIT
#pragma once
// The input deck of spec §9: `key = value` lines, `#` comments. Every error names the file, the
// line, the key and the value, and says what would fix it.
#include <stdexcept>
#include <string>

#include "inputs.hpp"

namespace cfe {

struct DeckError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Parse deck text; `file` is only used in messages. Throws DeckError.
Inputs parse_deck(const std::string& text, const std::string& file);
/// Read and parse a deck file. Throws DeckError (also when the file cannot be read).
Inputs read_deck(const std::string& path);

/// A deck for `in` in the layout of §9 (all 46 inputs, airbag_stiffness for spring), values
/// printed with 17 significant digits so that parse_deck(write_deck(in)) == in.
std::string write_deck(const Inputs& in);

}  // namespace cfe
