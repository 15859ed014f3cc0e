// SPDX-License-Identifier: MIT
// smi-lua libs: what a study run with the same --lib / SMI_PATH (and in the same folder, with
// its smi-libs/ and smi-lock.json) would see, and what is wrong; `libs tree` shows what requires
// what. The other subcommands (add, update, sync, remove, outdated, pack, registry, publish,
// search) are in commands_libs_*.cpp.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <set>
#include <string>

#include "cli/commands.hpp"

namespace smi::cli {
namespace {

const char* const kLibsUsage =
    "usage: smi-lua libs [add SOURCE[@REF] | add NAME[@RANGE] | update [NAME] | sync [--check] | tree | outdated | "
    "remove NAME[@VERSION] | pack DIR [FILE] | registry [NAME URL] | publish REGISTRY SOURCE@REF | search WORD]"
    " [--into DIR]";

/// What requires what, from the libraries a study would see: each library nobody requires at
/// the top, its requirements below it.
int libs_tree(const Args& a) {
  const vm::LibrarySet set = current_libraries(a);
  if (set.all().empty()) {
    std::printf("no libraries (none in ./smi-libs, smi-lock.json, --lib or SMI_PATH)\n");
    return 0;
  }
  std::set<std::string> required;
  for (const auto& l : set.all())
    for (const auto& r : l.manifest.requires_) required.insert(r.name);
  const std::function<void(const vm::Library&, const std::string&, std::set<std::string>&)> show =
      [&](const vm::Library& l, const std::string& indent, std::set<std::string>& path) {
        const auto& reqs = l.manifest.requires_;
        for (std::size_t i = 0; i < reqs.size(); ++i) {
          const vm::Requirement& r = reqs[i];
          const bool last = i + 1 == reqs.size();
          std::printf("%s%s", indent.c_str(), last ? "`-- " : "|-- ");
          const vm::Library* dep = r.name == "smi-lua" ? nullptr : set.find(r.name);
          if (r.name == "smi-lua") std::printf("smi-lua %s", vm::host_version());
          else if (!dep) std::printf("%s MISSING", r.name.c_str());
          else std::printf("%s %s", dep->name().c_str(), dep->manifest.version.text.c_str());
          const bool ok = r.name == "smi-lua" ? r.accepts(vm::Version::parse_loose(vm::host_version()))
                                              : dep && r.accepts(dep->manifest.version);
          std::printf("  (requires %s%s)\n", r.constraint().c_str(), ok ? "" : ", NOT MET");
          if (dep && !path.count(dep->name())) {
            path.insert(dep->name());
            show(*dep, indent + (last ? "    " : "|   "), path);
            path.erase(dep->name());
          }
        }
      };
  for (const auto& l : set.all()) {
    if (required.count(l.name())) continue;
    std::printf("%s %s", l.name().c_str(), l.manifest.version.text.c_str());
    if (!l.source.empty()) std::printf("  %s", l.source.c_str());
    if (!l.git.commit.empty()) std::printf(" @ %s", short_commit(l.git.commit).c_str());
    std::printf("\n");
    std::set<std::string> path = {l.name()};
    show(l, "", path);
  }
  std::fflush(stdout);
  const auto problems = set.problems();
  for (const auto& p : problems) std::fprintf(stderr, "smi-lua libs tree: %s\n", p.c_str());
  return problems.empty() ? 0 : 1;
}

}  // namespace

int cmd_libs(const Args& a, const std::vector<std::string>& all) {
  if (!all.empty()) {
    const std::string sub = all[0];
    const std::vector<std::string> args(all.begin() + 1, all.end());
    if (sub == "add") return libs_add(a, args);
    if (sub == "sync") return libs_sync(a, args);
    if (sub == "remove") return libs_remove(a, args);
    if (sub == "outdated") return libs_outdated(a, args);
    if (sub == "pack") return libs_pack(a, args);
    if (sub == "update") return libs_update(a, args);
    if (sub == "publish") return libs_publish(a, args);
    if (sub == "search") return libs_search(a, args);
    if (sub == "registry") return libs_registry(a, args);
    if (sub == "tree") {
      if (!args.empty()) {
        std::fprintf(stderr, "%s\n", kLibsUsage);
        return 2;
      }
      return libs_tree(a);
    }
    std::fprintf(stderr, "smi-lua libs: unknown subcommand '%s'\n%s\n", sub.c_str(), kLibsUsage);
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
