// SPDX-License-Identifier: MIT
#pragma once
// Where the REPL's lines come from: GNU readline on a terminal (editing, persistent history,
// tab completion, Ctrl-C clears the line), plain stdin otherwise (pipes, files: no prompts).
#include <optional>
#include <string>
#include <lua.hpp>

namespace smi::repl {

class LineReader {
 public:
  /// `L` is used for tab completion; history goes to SMI_HISTORY or ~/.smi_history.
  explicit LineReader(lua_State* L);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  /// The next line without its newline; nullopt at end of input. On a terminal, Ctrl-C at the
  /// prompt returns "" and sets interrupted().
  std::optional<std::string> read(const char* prompt);
  /// Adds a complete entry (possibly several lines) to the history and the history file.
  void remember(const std::string& entry);
  bool interactive() const { return tty_; }
  bool interrupted() const { return interrupted_; }

 private:
  bool tty_;
  bool interrupted_ = false;
  std::string history_file_;
};

}  // namespace smi::repl
