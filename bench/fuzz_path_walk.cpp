// SPDX-License-Identifier: MIT
// libFuzzer target over the sandbox's path resolver (host/platform/core/path_walk.cpp), with the
// kernel as oracle. Built and run by bench/run_fuzz_path_walk.sh (clang, -fsanitize=fuzzer,
// address, undefined); not part of the CMake build.
//
// A fixed tree is made once in a fresh temporary folder: a root with files, folders, symlinks
// that stay inside, lead out (absolute and relative), dangle, loop, point at folders and at
// "..", and an "outside" folder beside it. Each input is a path (first byte: follow_last) walked
// from inside the root. Checked on every input:
//  1. no crash, leak, overflow or undefined behaviour (the sanitizers);
//  2. agreement with the kernel: the object the walk reached is the object stat(2) (or lstat
//     without follow_last) reaches by the same path, same device and inode, and the walk finds
//     nothing where the kernel finds nothing (paths the kernel cannot take, over PATH_MAX,
//     are skipped);
//  3. the canonical path the walk reports names that same object (lstat of it agrees), so a
//     check of that path against a root is a check of the object opened;
//  4. the folder descriptor returned is the canonical folder (same inode).
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/path_walk.hpp"

namespace {

std::string g_root;

void sh(const std::string& cmd) {
  if (std::system(cmd.c_str()) != 0) {
    std::fprintf(stderr, "setup failed: %s\n", cmd.c_str());
    std::abort();
  }
}

void setup() {
  char tmpl[] = "/tmp/fuzz_path_walk.XXXXXX";
  const char* base = ::mkdtemp(tmpl);
  if (!base) std::abort();
  char real[PATH_MAX];
  if (!::realpath(base, real)) std::abort();
  const std::string b = real;
  g_root = b + "/root";
  sh("cd " + b + " && mkdir -p root/a/b/c root/d outside/o && echo s > outside/secret && echo f > root/a/f"
     " && echo g > root/a/b/g && cd root && ln -s a/b la && ln -s ../outside lo && ln -s " + b + "/outside/secret ls"
     " && ln -s missing dang && ln -s loop1 loop2 && ln -s loop2 loop1 && ln -s .. up && ln -s a/f lf"
     " && ln -s / slash && ln -s ../root/a rr && ln -s la/c lc && ln -s f a/b/self_f && ln -s ../../d a/b/dd"
     " && mkfifo d/fifo");
  if (::chdir(g_root.c_str()) != 0) std::abort();
}

bool same(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, size_t size) {
  if (g_root.empty()) setup();
  if (size == 0) return 0;
  const bool follow_last = data[0] & 1;
  std::string path(reinterpret_cast<const char*>(data) + 1, size - 1);
  // The kernel reads a name up to its NUL: compare only NUL-free names (the walk refuses NULs).
  const smi::pathwalk::Walk w = smi::pathwalk::walk(path, follow_last);
  if (path.find('\0') != std::string::npos) {
    if (w.error != EINVAL) std::abort();
    return 0;
  }
  if (path.empty() || path.size() >= 4000) return 0;
  struct stat k;
  const int krc = follow_last ? ::stat(path.c_str(), &k) : ::lstat(path.c_str(), &k);
  const int kerr = errno;
  if (w.error == ENAMETOOLONG || kerr == ENAMETOOLONG) return 0;  // limits differ by design
  const bool walk_found = w.error == 0 && w.exists;
  if (krc == 0) {
    if (!walk_found) {
      std::fprintf(stderr, "kernel finds '%s' (follow %d), the walk does not (error %d)\n", path.c_str(), follow_last,
                   w.error);
      std::abort();
    }
    if (!same(k, w.st)) {
      std::fprintf(stderr, "'%s': the walk reached another object than the kernel\n", path.c_str());
      std::abort();
    }
    struct stat c;
    if (::lstat(w.canonical().c_str(), &c) != 0 || !same(c, w.st)) {
      std::fprintf(stderr, "'%s': canonical '%s' names another object\n", path.c_str(), w.canonical().c_str());
      std::abort();
    }
    struct stat d, dc;
    if (::fstat(w.dir.get(), &d) != 0 || ::stat(w.dir_path.c_str(), &dc) != 0 || !same(d, dc)) {
      std::fprintf(stderr, "'%s': folder descriptor is not '%s'\n", path.c_str(), w.dir_path.c_str());
      std::abort();
    }
  } else if (walk_found && !(follow_last && S_ISLNK(w.st.st_mode))) {
    std::fprintf(stderr, "the walk finds '%s' (follow %d), the kernel does not (errno %d)\n", path.c_str(), follow_last,
                 kerr);
    std::abort();
  }
  return 0;
}
