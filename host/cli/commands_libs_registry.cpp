// SPDX-License-Identifier: MIT
// smi-lua libs registry / publish / search: team registries (vm/registry.hpp), git repositories
// holding an index of published library versions. `registry NAME URL` records one in the
// project's smi-project.json; `publish REGISTRY SOURCE@REF` adds a version (REGISTRY is a name
// recorded there, or a URL); `search WORD` lists the libraries of the project's registries whose
// name or description holds WORD.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "cli/commands.hpp"
#include "platform/core/errors.hpp"
#include "vm/library_sources.hpp"
#include "vm/manifest.hpp"
#include "vm/project_manifest.hpp"
#include "vm/registry.hpp"

namespace smi::cli {
namespace fs = std::filesystem;
namespace {

/// A temporary folder for git's clones and home, removed when done whatever happened.
struct TempFolder {
  fs::path dir;
  TempFolder() {
    const char* t = std::getenv("TMPDIR");
    std::string tmpl = (fs::path(t && *t ? t : "/tmp") / "smi-registry-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw Error("cannot create a temporary folder in " + fs::path(tmpl).parent_path().string());
    dir = tmpl;
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
};

fs::path manifest_here() { return fs::current_path() / vm::kProjectManifestName; }

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

int libs_registry(const Args&, const std::vector<std::string>& args) {
  if (args.size() != 0 && args.size() != 2) {
    std::fprintf(stderr, "usage: smi-lua libs registry [NAME URL]   (records a team registry in smi-project.json)\n");
    return 2;
  }
  vm::ProjectManifest m = vm::read_project_manifest(manifest_here());
  if (args.empty()) {
    if (m.registries.empty()) std::printf("no registries in %s\n", vm::kProjectManifestName);
    for (const auto& [name, url] : m.registries) std::printf("%s  %s\n", name.c_str(), url.c_str());
    return 0;
  }
  if (!vm::valid_library_name(args[0]))
    throw Error("registry name '" + args[0] + "': use letters, digits and '_' (not starting with a digit)");
  vm::check_git_address(args[1]);
  m.registries[args[0]] = args[1];
  vm::write_project_manifest(m, manifest_here());
  std::printf("%s: registry %s = %s\n", vm::kProjectManifestName, args[0].c_str(), args[1].c_str());
  return 0;
}

int libs_publish(const Args& a, const std::vector<std::string>& args) {
  if (args.size() != 2) {
    std::fprintf(stderr, "usage: smi-lua libs publish REGISTRY SOURCE@REF   (REGISTRY: a name in smi-project.json or "
                         "a git URL; SOURCE: the library's git repository as others reach it; REF: its version tag)\n");
    return 2;
  }
  const vm::ProjectManifest m = vm::read_project_manifest(manifest_here());
  const auto named = m.registries.find(args[0]);
  const std::string url = named != m.registries.end() ? named->second : args[0];
  const auto [source, ref] = vm::split_source_ref(args[1]);
  if (ref.empty())
    throw Error("'" + args[1] + "' names no version tag: publish SOURCE@TAG (e.g. " + source +
                "@v1.2.0), so that every team fetches the same commit");
  if (vm::source_kind(source, ref) != vm::SourceKind::git)
    throw Error("'" + source + "' is not a git repository: a registry records where other teams fetch the library, "
                "so publish the git address of the library's repository (file://, ssh:// or https://)");
  TempFolder tmp;
  const vm::GitPlace place{tmp.dir, a.cfg.timeout_s};
  const vm::Fetched f = vm::fetch_library(source, ref, tmp.dir / "lib", place);
  vm::RegistryEntry e;
  e.name = f.manifest.name;
  e.version = f.manifest.version.text;
  e.source = source;
  e.ref = ref;
  e.commit = f.commit;
  e.checksum = f.hash.digest;
  e.description = f.manifest.description;
  for (const auto& r : f.manifest.requires_) e.requires_.push_back(r.text);
  const vm::Registry reg = vm::Registry::clone(url, place, "registry");
  reg.publish(e);
  std::printf("published %s %s (%s at %s, commit %s, %zu files, %s) to %s\n", e.name.c_str(), e.version.c_str(),
              source.c_str(), ref.c_str(), e.commit.substr(0, 12).c_str(), f.hash.files.size(), e.checksum.c_str(),
              url.c_str());
  std::printf("other teams add it with: smi-lua libs add %s@^%s\n", e.name.c_str(), e.version.c_str());
  return 0;
}

int libs_search(const Args& a, const std::vector<std::string>& args) {
  if (args.size() != 1) {
    std::fprintf(stderr, "usage: smi-lua libs search WORD   (in the registries of smi-project.json)\n");
    return 2;
  }
  const vm::ProjectManifest m = vm::read_project_manifest(manifest_here());
  if (m.registries.empty())
    throw Error("the project names no registry to search (" + std::string(vm::kProjectManifestName) +
                "); add one: smi-lua libs registry NAME URL");
  TempFolder tmp;
  const vm::GitPlace place{tmp.dir, a.cfg.timeout_s};
  const std::string word = lower(args[0]);
  int found = 0;
  for (const auto& [rname, url] : m.registries) {
    const vm::Registry reg = vm::Registry::clone(url, place, "registry-" + rname);
    for (const std::string& name : reg.names()) {
      const std::vector<vm::RegistryEntry> vs = reg.versions(name);
      if (vs.empty()) continue;
      const vm::RegistryEntry& latest = vs.front();
      if (lower(name).find(word) == std::string::npos && lower(latest.description).find(word) == std::string::npos) continue;
      std::string all;
      for (const auto& v : vs) all += (all.empty() ? "" : ", ") + v.version;
      std::printf("%s %s  %s  [%s; versions: %s]\n", name.c_str(), latest.version.c_str(), latest.description.c_str(),
                  rname.c_str(), all.c_str());
      ++found;
    }
  }
  if (!found) std::printf("no library in the project's registries matches '%s'\n", args[0].c_str());
  return found ? 0 : 1;
}

}  // namespace smi::cli
