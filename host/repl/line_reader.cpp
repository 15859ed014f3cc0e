// SPDX-License-Identifier: MIT
#include "repl/line_reader.hpp"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>
// readline's headers need stdio first
#include <readline/history.h>
#include <readline/readline.h>

#include "repl/completion.hpp"

namespace smi::repl {
namespace {

lua_State* g_completion_state = nullptr;
volatile std::sig_atomic_t g_prompt_sigint = 0;
constexpr int kHistoryLength = 1000;

std::string g_before;  // the line before the word being completed (set by attempt_completion)

char* generator(const char* text, int state) {
  static std::vector<std::string> matches;
  static std::size_t next = 0;
  if (state == 0) {
    matches = g_completion_state ? complete_line(g_completion_state, text, g_before) : std::vector<std::string>{};
    next = 0;
  }
  return next < matches.size() ? strdup(matches[next++].c_str()) : nullptr;
}

char** attempt_completion(const char* text, int start, int) {
  g_before.assign(rl_line_buffer, static_cast<std::size_t>(start));
  rl_attempted_completion_over = 1;  // never fall back to file names
  rl_completion_append_character = '\0';  // readline resets it to ' ' before every attempt
  return rl_completion_matches(text, generator);
}

extern "C" void on_prompt_sigint(int) { g_prompt_sigint = 1; }

/// readline's character source: read(2) itself, so that Ctrl-C (EINTR, no SA_RESTART) can end
/// the line: the line is emptied and a newline returned, so readline hands back "".
int getc_interruptible(FILE* f) {
  for (;;) {
    unsigned char c;
    const ssize_t r = ::read(fileno(f), &c, 1);
    if (r == 1) return c;
    if (r == 0) return EOF;
    if (errno != EINTR) return EOF;
    if (g_prompt_sigint) {
      rl_replace_line("", 0);
      return '\n';
    }
  }
}

}  // namespace

LineReader::LineReader(lua_State* L) : tty_(::isatty(STDIN_FILENO) && ::isatty(STDOUT_FILENO)) {
  if (!tty_) return;
  g_completion_state = L;
  rl_readline_name = "smi-lua";
  rl_catch_signals = 0;  // SIGINT is ours: see getc_interruptible
  rl_getc_function = getc_interruptible;
  rl_attempted_completion_function = attempt_completion;
  rl_basic_word_break_characters = const_cast<char*>(" \t\n\"\\'`@$><=;|&{}()[],+-*/%^~#");
  // A quote before the word would be "remembered as the delimiter" and appended after a single
  // match (help("smi.ve<TAB> gave help("smi.vec"); the user closes the string, not readline.
  rl_basic_quote_characters = "";
  if (const char* h = std::getenv("SMI_HISTORY"))
    history_file_ = h;
  else if (const char* home = std::getenv("HOME"))
    history_file_ = std::string(home) + "/.smi_history";
  using_history();
  stifle_history(kHistoryLength);
  if (!history_file_.empty()) read_history(history_file_.c_str());
}

LineReader::~LineReader() {
  if (!tty_) return;
  if (!history_file_.empty()) history_truncate_file(history_file_.c_str(), kHistoryLength);
  g_completion_state = nullptr;
}

std::optional<std::string> LineReader::read(const char* prompt) {
  interrupted_ = false;
  if (!tty_) {
    std::string line;
    int c;
    while ((c = std::getchar()) != EOF && c != '\n') line += static_cast<char>(c);
    if (c == EOF && line.empty()) return std::nullopt;
    return line;
  }
  struct sigaction sa {}, old {};
  sa.sa_handler = on_prompt_sigint;  // no SA_RESTART: read(2) returns EINTR
  sigemptyset(&sa.sa_mask);
  g_prompt_sigint = 0;
  sigaction(SIGINT, &sa, &old);
  char* line = readline(prompt);
  sigaction(SIGINT, &old, nullptr);
  interrupted_ = g_prompt_sigint != 0;
  if (!line) return std::nullopt;
  std::string s = line;
  std::free(line);
  return s;
}

void LineReader::remember(const std::string& entry) {
  if (!tty_ || entry.empty()) return;
  add_history(entry.c_str());
  if (!history_file_.empty()) {
    // append, creating the file on first use
    if (append_history(1, history_file_.c_str()) != 0) write_history(history_file_.c_str());
  }
}

}  // namespace smi::repl
