// SPDX-License-Identifier: MIT
#include "vm/build_info.hpp"

#include <Eigen/Core>
#include <fmt/format.h>
#include <lua.hpp>
#include <nettle/version.h>
#include <nlopt.h>
#include <sqlite3.h>

#include "vm/libraries.hpp"

#ifndef SMI_BUILD_TYPE
#define SMI_BUILD_TYPE "unknown"
#endif
#ifndef SMI_RE2_VERSION
#define SMI_RE2_VERSION "unknown"  // RE2 has no version call: CMake passes pkg-config's
#endif

namespace smi::vm {

namespace {
std::string compiler() {
#if defined(__clang__)
  return std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("GCC ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}
}  // namespace

std::vector<std::pair<std::string, std::string>> build_info() {
  int nmaj = 0, nmin = 0, nbug = 0;
  nlopt_version(&nmaj, &nmin, &nbug);  // the library linked, not the header
  return {
      {"smi-lua", host_version()},
      {"build", SMI_BUILD_TYPE},
      {"compiler", compiler()},
      {"lua", LUA_RELEASE},
      {"eigen", fmt::format("{}.{}.{}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)},
      {"nlopt", fmt::format("{}.{}.{}", nmaj, nmin, nbug)},
      {"sqlite", sqlite3_libversion()},
      {"re2", SMI_RE2_VERSION},
      {"nettle", fmt::format("{}.{}", nettle_version_major(), nettle_version_minor())},
      {"fmt", fmt::format("{}.{}.{}", FMT_VERSION / 10000, FMT_VERSION / 100 % 100, FMT_VERSION % 100)},
  };
}

std::string build_line() {
  static const std::pair<const char*, const char*> kShown[] = {
      {"eigen", "Eigen"}, {"nlopt", "NLopt"}, {"sqlite", "SQLite"}, {"re2", "RE2"}, {"nettle", "nettle"}, {"fmt", "fmt"}};
  const auto info = build_info();
  std::string s = "smi-lua " + info[0].second + " (";
  for (std::size_t i = 1; i < info.size(); ++i) {
    if (i > 1) s += "; ";
    std::string name;
    for (const auto& [k, shown] : kShown)
      if (info[i].first == k) name = shown;
    s += name.empty() ? info[i].second : name + " " + info[i].second;  // build type, compiler, Lua: as they are
  }
  return s + ")";
}

}  // namespace smi::vm
