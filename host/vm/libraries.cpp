#include "vm/libraries.hpp"

#include <algorithm>

#include "kernels/core/errors.hpp"
#include "luax/policy.hpp"

#ifndef SMI_VERSION
#define SMI_VERSION "0.0.0"
#endif

namespace smi::vm {
namespace fs = std::filesystem;

const char* host_version() { return SMI_VERSION; }

const FolderHash& Library::hash() const {
  if (!hash_cache) hash_cache = hash_folder(folder);
  return *hash_cache;
}

std::string Library::describe() const {
  return manifest.name + " " + manifest.version.text + " at " + folder.string() + " (" + root.origin + " " + root.dir + ")";
}

std::vector<LibraryRoot> library_roots(const std::vector<std::string>& lib_dirs, const char* smi_path_env) {
  std::vector<LibraryRoot> out;
  for (const auto& d : lib_dirs) out.push_back({d, "--lib"});
  if (smi_path_env) {
    const std::string s = smi_path_env;
    std::size_t start = 0;
    for (;;) {
      const std::size_t end = s.find(':', start);
      const std::string part = s.substr(start, end == std::string::npos ? std::string::npos : end - start);
      if (!part.empty()) out.push_back({part, "SMI_PATH"});
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  return out;
}

LibrarySet LibrarySet::discover(const std::vector<LibraryRoot>& roots) {
  LibrarySet set;
  set.roots_ = roots;
  const auto add = [&](const fs::path& folder, const LibraryRoot& root) {
    Library lib;
    lib.folder = resolve_path(folder.string());
    // The same folder reached twice (--lib and SMI_PATH naming it) is one library, not a conflict.
    for (const Library& l : set.libs_)
      if (l.folder == lib.folder) return;
    lib.manifest = read_manifest(lib.folder / kManifestName);
    lib.root = root;
    lib.git = git_info(lib.folder);
    set.libs_.push_back(std::move(lib));
  };
  for (const LibraryRoot& root : roots) {
    std::error_code ec;
    const fs::path dir(root.dir);
    if (fs::is_regular_file(dir / kManifestName, ec)) {
      add(dir, root);
      continue;
    }
    if (!fs::is_directory(dir, ec)) continue;  // a missing folder finds nothing (as for plain modules)
    std::vector<fs::path> subs;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.is_directory(ec) && fs::is_regular_file(e.path() / kManifestName, ec)) subs.push_back(e.path());
    std::sort(subs.begin(), subs.end());  // a stable order, whatever the file system's
    for (const auto& s : subs) add(s, root);
  }
  return set;
}

const Library* LibrarySet::find(const std::string& name) const {
  for (const Library& l : libs_)
    if (l.name() == name) return &l;
  return nullptr;
}

std::vector<std::string> LibrarySet::problems() const {
  std::vector<std::string> out;
  std::string searched;
  for (const auto& r : roots_) searched += (searched.empty() ? "" : ", ") + r.origin + " " + r.dir;
  for (std::size_t i = 0; i < libs_.size(); ++i) {
    const Library& a = libs_[i];
    if (a.name() == "smi")
      out.push_back("library at " + a.folder.string() + " is named 'smi', which is reserved for the smi stdlib; "
                    "rename it in " + a.manifest.file.string());
    for (std::size_t j = 0; j < i; ++j) {
      const Library& b = libs_[j];
      if (b.name() != a.name()) continue;
      out.push_back("two copies of library '" + a.name() + "': " + b.describe() + " and " + a.describe() +
                    "; a study sees one version of each library: remove one of the two folders from --lib / "
                    "SMI_PATH (smi-lua -E ignores SMI_PATH)");
    }
  }
  for (const Library& a : libs_) {
    for (const Requirement& r : a.manifest.requires_) {
      const std::string who = "library " + a.name() + " " + a.manifest.version.text + " (" + a.manifest.file.string() +
                              ") requires '" + r.text + "'";
      if (r.name == "smi-lua") {
        const Version host = Version::parse_loose(host_version());
        if (!r.accepts(host))
          out.push_back(who + ", but this is smi-lua " + host.text + "; use an smi-lua with " + r.constraint() +
                        " or a release of " + a.name() + " made for smi-lua " + host.text);
        continue;
      }
      const Library* dep = find(r.name);
      if (!dep) {
        out.push_back(who + ", but no library '" + r.name + "' is on the library path (" +
                      (searched.empty() ? std::string("no --lib folder or SMI_PATH entry") : searched) +
                      "); add the folder holding it with --lib DIR or to SMI_PATH");
      } else if (!r.accepts(dep->manifest.version)) {
        out.push_back(who + ", but " + dep->describe() + " does not satisfy " + r.constraint() + "; put a version of " +
                      r.name + " with " + r.constraint() + " on the library path (e.g. check out a matching tag in " +
                      dep->folder.string() + "), or use a release of " + a.name() + " that accepts " + r.name + " " +
                      dep->manifest.version.text);
      }
    }
  }
  return out;
}

void LibrarySet::check() const {
  const std::vector<std::string> p = problems();
  if (p.empty()) return;
  std::string msg = p.size() == 1 ? "library problem, the study was not started:" : std::to_string(p.size()) +
                                                                                       " library problems, the study was not started:";
  for (const auto& s : p) msg += "\n  " + s;
  throw Error(msg);
}

}  // namespace smi::vm
