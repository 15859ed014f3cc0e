// SPDX-License-Identifier: MIT
#pragma once
// A folder under /tmp for one test case, removed with everything in it when the case ends
// (the library tests build manifests, git repositories and archives in it).
#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>

struct TempDir {
  std::filesystem::path p;
  TempDir() {
    char tmpl[] = "/tmp/smi-libs-XXXXXX";
    p = ::mkdtemp(tmpl);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(p, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};
