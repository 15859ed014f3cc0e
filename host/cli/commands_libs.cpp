// smi-lua libs: what a study run with the same --lib / SMI_PATH would see, and what is wrong.
#include <algorithm>
#include <cstdio>
#include <string>

#include "cli/commands.hpp"

namespace smi::cli {

int cmd_libs(const Args& a, const std::vector<std::string>& args) {
  if (!args.empty()) {
    std::fprintf(stderr, "smi-lua libs: takes no arguments (got '%s'); give folders with --lib DIR\n", args[0].c_str());
    return 2;
  }
  const vm::LibrarySet set = current_libraries(a);
  if (set.all().empty()) {
    std::printf("no libraries on the library path");
    if (set.roots().empty()) std::printf(" (add folders with --lib DIR or SMI_PATH=DIR:DIR)");
    std::printf("\n");
  } else {
    std::size_t wn = 4, wv = 7;
    for (const auto& l : set.all()) {
      wn = std::max(wn, l.name().size());
      wv = std::max(wv, l.manifest.version.text.size());
    }
    std::printf("%-*s  %-*s  %-12s  %s\n", int(wn), "NAME", int(wv), "VERSION", "COMMIT", "PATH");
    for (const auto& l : set.all()) {
      const std::string commit = l.git.commit.empty() ? "-" : l.git.commit.substr(0, 12);
      std::printf("%-*s  %-*s  %-12s  %s\n", int(wn), l.name().c_str(), int(wv), l.manifest.version.text.c_str(),
                  commit.c_str(), l.folder.string().c_str());
    }
  }
  for (const auto& r : set.roots()) std::printf("searched: %s %s\n", r.origin.c_str(), r.dir.c_str());
  std::fflush(stdout);
  const auto problems = set.problems();
  for (const auto& p : problems) std::fprintf(stderr, "smi-lua libs: %s\n", p.c_str());
  return problems.empty() ? 0 : 1;
}

}  // namespace smi::cli
