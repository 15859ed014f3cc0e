// SPDX-License-Identifier: MIT
// --max-memory is checked before the allocation: each binding that allocates
// a size the script chose asks the budget first, inside protect(). The old bindings allocated
// the whole result and counted it when pushing it, so a study under --max-memory 64 reached
// 1 GB before being refused (and smi.vec.range failed with the error value "1"). Each case asks
// for about 0.5-1 GB under --max-memory 64: the run must end with the memory message naming
// the function, and its peak resident size (wait4's ru_maxrss) stay far below the request.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fcntl.h>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

struct Result {
  int status = -1;
  long max_rss_kb = 0;
  std::string err;
};

Result run_smi(const std::string& code) {
  char tmpl[] = "/tmp/smi_memory_first.XXXXXX";
  const int fd = ::mkstemp(tmpl);
  REQUIRE(fd >= 0);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::dup2(fd, 2);
    const int null = ::open("/dev/null", O_RDWR);
    ::dup2(null, 0);
    ::dup2(null, 1);
    ::execl(SMI_LUA_PATH, "smi-lua", "--quiet", "--max-memory", "64", "-e", code.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  Result r;
  int st = 0;
  rusage ru{};
  REQUIRE(::wait4(pid, &st, 0, &ru) == pid);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  r.max_rss_kb = ru.ru_maxrss;
  char buf[4096];
  ::lseek(fd, 0, SEEK_SET);
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) r.err.append(buf, static_cast<std::size_t>(n));
  ::close(fd);
  ::unlink(tmpl);
  return r;
}

}  // namespace

TEST_CASE("every allocating binding refuses before allocating under --max-memory") {
  struct Case {
    const char* code;
    const char* fname;
  };
  const Case cases[] = {
      {"smi.dist.normal{mean = 0, std = 1}:sample(2^27, 1)", "dist:sample"},
      {"smi.vec.range(1, 2^27)", "smi.vec.range"},
      {"smi.vec.range(0, 1, 1e-8)", "smi.vec.range"},
      {"local s = {} for i = 1, 8 do s[i] = {0, 1} end smi.doe.sobol(1 << 24, s)", "smi.doe.sobol"},
      {"local s = {} for i = 1, 8 do s[i] = {0, 1} end smi.doe.lhs(1 << 24, s, {criterion = 'none'})", "smi.doe.lhs"},
      {"smi.doe.full_factorial(64, {{0, 1}, {0, 1}, {0, 1}, {0, 1}})", "smi.doe.full_factorial"},
      {"smi.propagate{model = function(M) return {y = M:col(1)} end, inputs = {{'a', smi.dist.normal{mean = 0, std = 1}}}, "
       "n = 2^26}",
       "smi.propagate"},
  };
  for (const Case& c : cases) {
    INFO(c.code);
    const Result r = run_smi(c.code);
    INFO(r.err);
    CHECK(r.status == 1);
    CHECK(r.err.find(std::string(c.fname) + ": memory limit exceeded") != std::string::npos);
    CHECK(r.max_rss_kb < 300 * 1024);
  }
}
