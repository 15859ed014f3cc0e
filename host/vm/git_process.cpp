// SPDX-License-Identifier: MIT
#include "vm/git_process.hpp"

#include <cstdlib>
#include <cstring>
#include <unistd.h>

#include "platform/core/errors.hpp"
#include "platform/eval/process.hpp"

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

constexpr const char* kAllowedProtocols = "file:https:ssh";

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

std::string find_git() {
  const std::string git = eval::find_program("git");
  if (git.empty())
    throw Error("the git program is not on PATH: install git (apt-get install git) to add libraries from git "
                "repositories, or give a folder or a .tar.gz made by smi-lua libs pack");
  return git;
}

}  // namespace

std::string git_reason(const std::string& s) {
  const std::size_t f = s.find("fatal: ");
  if (f != std::string::npos) return trim(s.substr(f + 7, s.find('\n', f) - f - 7));
  std::string t = trim(s);
  const std::size_t nl = t.rfind('\n');
  return nl == std::string::npos ? t : t.substr(nl + 1);
}

void check_git_address(const std::string& address) {
  if (address.find('\0') != std::string::npos)
    throw Error("a library source holds a NUL byte, so it is no address; write it as text");
  if (!address.empty() && address[0] == '-')
    throw Error("'" + address + "' is not a library source (it starts with '-'); write ./" + address + " for a folder");
  // git reads "<transport>::<address>" as "run the program git-remote-<transport>"
  const std::size_t helper = address.find("::");
  if (helper != std::string::npos && address.find('/') > helper)
    throw Error("'" + address + "' names the git remote helper '" + address.substr(0, helper) +
                "', and smi-lua lets git use only file, https and ssh addresses (a helper runs a program); "
                "give the repository's https://, ssh:// or file:// address, or a folder");
}

GitResult run_git(const std::vector<std::string>& args, const GitPlace& place) {
  const std::string git = find_git();
  const fs::path home = place.scratch / "home";
  fs::create_directories(home);
  std::vector<std::string> argv = {"git",
                                   "-c", "core.hooksPath=/dev/null",
                                   "-c", "core.symlinks=false",
                                   "-c", "core.fsmonitor=false",
                                   "-c", "protocol.allow=never",
                                   "-c", "protocol.file.allow=always",
                                   "-c", "protocol.https.allow=always",
                                   "-c", "protocol.ssh.allow=always",
                                   "-c", "credential.helper=",
                                   "-c", "advice.detachedHead=false"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<std::string> env = {"HOME=" + home.string(), "GIT_CONFIG_NOSYSTEM=1", "GIT_CONFIG_GLOBAL=/dev/null",
                                  "GIT_TERMINAL_PROMPT=0", std::string("GIT_ALLOW_PROTOCOL=") + kAllowedProtocols,
                                  "LANG=C", "LC_ALL=C"};
  for (const char* keep : {"PATH", "SSH_AUTH_SOCK", "http_proxy", "https_proxy", "no_proxy", "HTTP_PROXY",
                           "HTTPS_PROXY", "NO_PROXY"})
    if (const char* v = std::getenv(keep)) env.push_back(std::string(keep) + "=" + v);
  // Started the evaluator's way (platform/eval/process.hpp): own process group, default
  // signals, exactly this environment, both outputs captured, killed at the time limit.
  eval::SpawnSpec spec;
  spec.program = git;
  spec.argv = std::move(argv);
  spec.env = std::move(env);
  spec.solver_mark = false;
  const double limit = place.timeout_s > 0 ? place.timeout_s : kDefaultGitTimeout;
  eval::CapturedRun c;
  try {
    c = eval::run_captured(std::move(spec), limit);
  } catch (const eval::SpawnError& e) {
    throw Error("cannot run " + git + ": " + std::strerror(e.err));
  }
  if (c.timed_out) {
    std::string what = "git";
    for (const auto& a : args) what += " " + a;
    throw Error("'" + what + "' did not finish within " + std::to_string(static_cast<long>(limit)) +
                " s and was stopped; check that the address answers, or give a longer --timeout SECONDS");
  }
  GitResult r;
  r.status = c.status > 128 ? 128 : c.status;  // killed by a signal: 128
  r.out = std::move(c.out);
  r.err = std::move(c.err);
  return r;
}

}  // namespace smi::vm
