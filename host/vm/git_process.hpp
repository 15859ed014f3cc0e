// SPDX-License-Identifier: MIT
#pragma once
// Every git command smi-lua runs (fetching libraries, reading and writing a team registry) goes
// through run_git, which fixes how git may behave whatever the repository or the user's setup:
//
// - a minimal environment: HOME is an empty folder of the caller's scratch space, no system or
//   global configuration (GIT_CONFIG_NOSYSTEM, GIT_CONFIG_GLOBAL=/dev/null), no terminal
//   prompt; only PATH, LANG=C, SSH_AUTH_SOCK and the proxy variables are passed on;
// - no hooks (core.hooksPath=/dev/null; clones take an empty --template), no fsmonitor, no
//   credential helper, symlinks checked out as plain files;
// - a protocol allow-list: file, https and ssh only (GIT_ALLOW_PROTOCOL, and protocol.allow=never
//   with one entry per allowed protocol), so no remote helper (`fd::`, `ext::`, `foo::`) runs;
//   a source spelled as a remote helper is refused before git starts;
// - a time limit: the process group is killed when it runs out (the run's --timeout, or
//   kDefaultGitTimeout), so an address that never answers stops with a message.
#include <filesystem>
#include <string>
#include <vector>

namespace smi::vm {

inline constexpr double kDefaultGitTimeout = 300;  // seconds, when the command line gives no --timeout

/// Where git runs: `scratch` (an existing folder) holds its empty home; `timeout_s` bounds each call.
struct GitPlace {
  std::filesystem::path scratch;
  double timeout_s = kDefaultGitTimeout;
};

struct GitResult {
  int status = -1;
  std::string out, err;
};

/// Runs git with `args` as described above (never through a shell). A call that runs out of
/// time throws smi::Error naming the command and the limit.
GitResult run_git(const std::vector<std::string>& args, const GitPlace& place);

/// Throws smi::Error when `address` is no repository address git may use here: one starting
/// with '-' (an option), or a remote helper ("fd::7", "ext::sh -c ...").
void check_git_address(const std::string& address);

/// git's reason for a failure: its first "fatal: ..." line, else the last line of its errors.
std::string git_reason(const std::string& err);

}  // namespace smi::vm
