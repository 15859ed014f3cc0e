// SPDX-License-Identifier: MIT
#pragma once
// Input-deck templates: text with named placeholders {{name}} or {{name:%.6E}} that are filled
// with a point's inputs (numbers) and a model's constants (numbers or strings). Rendering is
// plain text substitution into a file: no shell and no evaluation ever sees a value, so a value
// such as "$(rm -rf ~)" lands in the deck exactly as written.
#include <map>
#include <string>
#include <vector>

#include "platform/core/errors.hpp"

namespace smi::eval {

/// A template problem; the message names the template file, the line and the placeholder.
struct TemplateError : Error {
  using Error::Error;
};

/// A value for a placeholder: a number (formatted with the placeholder's format, default %.17g
/// so the deck holds the exact double) or a string (inserted as is; one line, no NUL).
struct DeckValue {
  bool is_number = true;
  double number = 0;
  std::string text;
  static DeckValue num(double v) { return {true, v, {}}; }
  static DeckValue str(std::string s) { return {false, 0, std::move(s)}; }
};

using DeckValues = std::map<std::string, DeckValue, std::less<>>;

class DeckTemplate {
 public:
  /// Parses `text`; `source` names it in errors (a file path or "(template_string)").
  /// Throws TemplateError for an unterminated {{, a bad name or a bad format.
  DeckTemplate(std::string text, std::string source);

  /// Reads and parses a template file.
  static DeckTemplate from_file(const std::string& path);

  /// The text with every placeholder replaced. Throws TemplateError naming source, line and
  /// placeholder for a missing value, a number format given a string, %d given a non-integer,
  /// a non-finite number, or a string holding a line break.
  std::string render(const DeckValues& values) const;

  /// Distinct placeholder names in order of first appearance.
  std::vector<std::string> names() const;
  bool uses(const std::string& name) const;
  const std::string& source() const { return source_; }

 private:
  struct Piece {
    bool literal;
    std::string text;    // literal text, or the placeholder name
    std::string format;  // printf format ("" = default)
    int line;
  };
  std::vector<Piece> pieces_;
  std::string source_;
};

}  // namespace smi::eval
