// SPDX-License-Identifier: MIT
// The REPL as a person uses it, through a pseudo-terminal (readline active): tab completion of
// globals, nested fields and methods, multi-line input, printing without '=', Ctrl-C stopping a
// running chunk and clearing the prompt line while the session goes on, persistent history,
// and the sandbox.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <poll.h>
#include <pty.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

/// smi-lua running on the slave side of a pty; we read and type on the master side.
class Session {
 public:
  /// `cwd`: the folder the REPL runs in (default: the test's own).
  explicit Session(const std::string& history, const std::string& cwd = "") {
    struct winsize ws {};
    ws.ws_row = 40;
    ws.ws_col = 200;
    pid_ = forkpty(&fd_, nullptr, nullptr, &ws);
    REQUIRE(pid_ >= 0);
    if (pid_ == 0) {
      setenv("TERM", "dumb", 1);
      setenv("SMI_HISTORY", history.c_str(), 1);
      if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(126);
      execl(SMI_LUA_PATH, "smi-lua", static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  ~Session() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    close(fd_);
  }

  void type(const std::string& keys) {
    REQUIRE(write(fd_, keys.data(), keys.size()) == static_cast<ssize_t>(keys.size()));
  }

  /// Reads until `text` appears after the previous match; false after `seconds` (generous: a
  /// sanitizer build on a loaded 2-core machine parses the help texts in several seconds).
  bool expect(const std::string& text, double seconds = 30) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
      const std::size_t at = out_.find(text, mark_);
      if (at != std::string::npos) {
        mark_ = at + text.size();
        return true;
      }
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      if (left.count() <= 0) return false;
      struct pollfd p {fd_, POLLIN, 0};
      if (poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
      char buf[4096];
      const ssize_t n = read(fd_, buf, sizeof buf);
      if (n <= 0) return false;
      out_.append(buf, static_cast<std::size_t>(n));
    }
  }

  /// Waits for the program to end; returns its exit status (or -1).
  int wait_exit(double seconds = 30) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      char buf[4096];
      struct pollfd p {fd_, POLLIN, 0};
      ssize_t n = 0;
      if (poll(&p, 1, 50) > 0 && (n = read(fd_, buf, sizeof buf)) > 0) out_.append(buf, static_cast<std::size_t>(n));
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
    }
    return -1;
  }

  const std::string& transcript() const { return out_; }
  bool running() const { return pid_ > 0; }

  /// Ctrl-D until the program ends, as a person presses it again: a Ctrl-D that reaches the
  /// terminal while readline is between lines is consumed by the line discipline (seen on a
  /// loaded CI machine after a Ctrl-C). Returns the exit status, or -1.
  int quit() {
    for (int i = 0; i < 5 && running(); ++i) {
      // not type(): the program may be ending, and a write to its closed terminal may fail
      if (write(fd_, "\x04", 1) != 1) return wait_exit(10);
      const int status = wait_exit(10);
      if (!running()) return status;
    }
    return -1;
  }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string out_;
  std::size_t mark_ = 0;
};

std::string temp_history() {
  char tmpl[] = "/tmp/smi_history_XXXXXX";
  const int fd = mkstemp(tmpl);
  close(fd);
  return tmpl;
}

// An expression is printed without '='; tab completes a global, a nested field, a method.
void check_printing_and_completion(Session& s) {
  // an expression is printed without '='
  s.type("6 * 7\n");
  CHECK(s.expect("42"));

  // tab completion: a global, a nested field, a method of a userdata
  s.type("prin\t('completed')\n");
  CHECK(s.expect("print('completed')"));
  CHECK(s.expect("completed"));
  s.type("smi.vec.linsp\t(0, 1, 3)\n");
  CHECK(s.expect("smi.vec.linspace(0, 1, 3)"));
  CHECK(s.expect("vec(3)[0, 0.5, 1]"));
  s.type("v = smi.vec{1, 2, 3}\n");
  s.type("v:cums\t()\n");
  CHECK(s.expect("v:cumsum()"));
  CHECK(s.expect("vec(3)[1, 3, 6]"));
}

// Multi-line chunks get the second prompt; tables print bounded and readable.
void check_multiline_and_tables(Session& s) {
  // multi-line input: the second prompt until the chunk is complete
  s.type("function twice(a)\n");
  CHECK(s.expect(">> "));
  s.type("return a * 2\n");
  CHECK(s.expect(">> "));
  s.type("end\n");
  s.type("twice(21.5)\n");
  CHECK(s.expect("43"));

  // tables print bounded and readable
  s.type("t = {1, 2, a = {b = 'x'}}\n");
  s.type("t\n");
  CHECK(s.expect("{1, 2, a = {b = \"x\"}}"));
  s.type("smi.vec.linspace(0, 1, 1000000)\n");
  CHECK(s.expect("vec(1000000)["));
}

// Runs `chunk`, stops it with Ctrl-C, then checks the session goes on: `probe` prints `want`.
void interrupt_then(Session& s, const std::string& chunk, const std::string& probe, const std::string& want) {
  s.type(chunk + "\n");
  usleep(300 * 1000);
  s.type("\x03");
  CHECK(s.expect("interrupted!"));
  s.type(probe + "\n");
  CHECK(s.expect(want));
}

// Ctrl-C stops a running chunk (plain, under pcall, in a coroutine) and the session goes on.
void check_interrupting_chunks(Session& s) {
  interrupt_then(s, "while true do end", "'still alive'", "still alive");
  // ... even when the chunk swallows errors with pcall
  interrupt_then(s, "while true do pcall(function() while true do end end) end", "100 + 1", "101");
  // ... and when the loop runs inside a coroutine
  interrupt_then(s, "coroutine.wrap(function() while true do end end)()", "100 + 2", "102");
}

// Ctrl-C at the prompt drops the half-typed line, also inside a multi-line chunk.
void check_ctrl_c_at_prompt(Session& s) {
  // Ctrl-C at the prompt drops the half-typed line, also inside a multi-line chunk
  s.type("this is not lua");
  usleep(100 * 1000);
  s.type("\x03");
  usleep(200 * 1000);  // the terminal flushes input typed right after Ctrl-C, as a person would not
  s.type("2 ^ 10\n");
  CHECK(s.expect("1024.0"));
  s.type("for i = 1, 3 do\n");
  CHECK(s.expect(">> "));
  s.type("\x03");
  usleep(200 * 1000);
  s.type("'fresh'\n");
  CHECK(s.expect("fresh"));
}

// The same sandbox as scripts.
void check_sandbox(Session& s) {
  // the same sandbox as scripts
  s.type("io.open('/etc/passwd')\n");
  CHECK(s.expect("is not allowed"));
  s.type("io.popen\n");
  CHECK(s.expect("nil"));
  CHECK(s.expect("> "));  // ^D typed before readline owns the terminal could be lost
}

}  // namespace

TEST_CASE("REPL: completion, multi-line input, printing, Ctrl-C, sandbox, history") {
  const std::string history = temp_history();
  {
    Session s(history);
    INFO(s.transcript());
    REQUIRE(s.expect("smi-lua "));
    REQUIRE(s.expect("> "));

    check_printing_and_completion(s);
    check_multiline_and_tables(s);
    check_interrupting_chunks(s);
    check_ctrl_c_at_prompt(s);
    check_sandbox(s);
    const int status = s.quit();  // Ctrl-D: end of input
    CHECK(status == 0);
    if (status != 0) std::fprintf(stderr, "transcript:\n%s\n", s.transcript().c_str());
  }

  // the history file holds the entries, and a new session recalls them (Ctrl-P)
  std::ifstream h(history);
  std::stringstream all;
  all << h.rdbuf();
  CHECK(all.str().find("twice(21.5)") != std::string::npos);
  CHECK(all.str().find("return a * 2") != std::string::npos);  // multi-line entries are kept whole
  {
    Session s(history);
    INFO(s.transcript());
    REQUIRE(s.expect("> "));
    s.type("\x10\n");  // previous entry: 'fresh'... then the sandbox lines; recall the last one
    CHECK(s.expect("nil"));
    s.type("os.exit(3)\n");
    CHECK(s.wait_exit() == 3);
  }
  std::remove(history.c_str());
}

TEST_CASE("REPL: help(), ?name, help \"word\" and completion inside help(") {
  const std::string history = temp_history();
  Session s(history);
  INFO(s.transcript());
  REQUIRE(s.expect("> "));

  // help(value): the entry, with each option's default (read from the kernel's option struct)
  s.type("help(smi.kde_bd)\n");
  CHECK(s.expect("smi.kde_bd(data, opts) -> dist, info"));
  CHECK(s.expect("critical_area = 0.95"));
  CHECK(s.expect("example:"));
  // a method through a value the user holds
  s.type("v = smi.vec{1, 2}\n");
  s.type("help(v.cumsum)\n");
  CHECK(s.expect("smi.vec:cumsum() -> vec"));
  // ?name, as in trepl; the history keeps what was typed
  s.type("?smi.rng\n");
  CHECK(s.expect("smi.rng(seed [, stream]) -> rng"));
  s.type("? v:quantile\n");
  CHECK(s.expect("Type-7 quantiles"));
  // a word searches every text
  s.type("help \"bandwidth\"\n");
  CHECK(s.expect("entries mention 'bandwidth'"));
  CHECK(s.expect("smi.bandwidth"));
  // help(): the modules, one line each
  s.type("help()\n");
  CHECK(s.expect("smi.calibrate"));
  CHECK(s.expect("smi.vec"));
  CHECK(s.expect("> "));

  // completion inside help( ... ): values as anywhere, doc names inside a string and after ?
  s.type("help(smi.kde_e\t)\n");
  CHECK(s.expect("help(smi.kde_ebd)"));
  CHECK(s.expect("alpha = 0.1"));
  s.type("help(\"smi.vec:cums\t\")\n");
  CHECK(s.expect("help(\"smi.vec:cumsum\")"));
  CHECK(s.expect("Cumulative sums"));
  s.type("?smi.metric.upool_th\t\n");
  CHECK(s.expect("?smi.metric.upool_threshold"));
  CHECK(s.expect("smi.metric.upool_threshold(n, confidence [, opts]) -> U_crit"));

  // Ctrl-D only after the next prompt: typed earlier, it reaches the terminal while readline has
  // it in canonical mode between lines, where the line discipline consumes it (a lost EOF). The
  // prompt is matched at a line's start: the entry just printed holds "-> U_crit", whose "> "
  // matched first and sent Ctrl-D early on a loaded machine (a 30 s wait, then exit -1).
  CHECK(s.expect("\n> "));
  CHECK(s.quit() == 0);
  std::ifstream h(history);
  std::stringstream all;
  all << h.rdbuf();
  CHECK(all.str().find("?smi.rng") != std::string::npos);
  std::remove(history.c_str());
}

TEST_CASE("REPL: an error is one line; Ctrl-C says only what is true") {
  const std::string history = temp_history();
  char dir[] = "/tmp/smi_repl_cwd_XXXXXX";  // a fresh folder: no output folder, no store exists
  REQUIRE(mkdtemp(dir) != nullptr);
  {
    Session s(history, dir);
    INFO(s.transcript());
    REQUIRE(s.expect("> "));
    s.type("error('boom in my code')\n");
    CHECK(s.expect("boom in my code"));
    s.type("smi.fail('tests.csv: no column mode2_Hz')\n");
    CHECK(s.expect("smi-lua: tests.csv: no column mode2_Hz"));
    s.type("'after the errors'\n");
    CHECK(s.expect("after the errors"));
    interrupt_then(s, "while true do end", "'after Ctrl-C'", "after Ctrl-C");
    const std::string t = s.transcript();
    CHECK(t.find("stack traceback") == std::string::npos);  // one line each
    CHECK(t.find("evaluations.sqlite") == std::string::npos);  // no store was made: none is named
    CHECK(t.find("results.json") == std::string::npos);
    // Ctrl-D only after the next prompt at a line's start ("> " alone also matches the echo of
    // the typed line, and a Ctrl-D sent then is consumed between lines: a lost EOF, exit -1 after
    // 30 s on a loaded CI machine)
    CHECK(s.expect("\n> "));
    CHECK(s.quit() == 0);
  }
  rmdir(dir);
  std::remove(history.c_str());
}
