// SPDX-License-Identifier: MIT
#include "vm/libraries.hpp"

#include <algorithm>
#include <map>

#include <cerrno>
#include <sys/stat.h>

#include "luax/policy.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/path_walk.hpp"

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

namespace {

/// Throws when the project's tree (`rel` below the canonical project folder `dir`) is a symbolic
/// link or is reached through one: a link would make any folder a read root of the study.
void check_project_tree(const fs::path& dir, const fs::path& rel) {
  const fs::path want = (dir / rel).lexically_normal();
  const pathwalk::Walk w = pathwalk::walk(want.string(), false);
  if (w.error == ENOENT || (!w.error && !w.exists)) return;  // no tree yet
  if (!w.error && !S_ISLNK(w.st.st_mode) && S_ISDIR(w.st.st_mode) && w.canonical() == want.string()) return;
  throw Error("the library tree '" + want.string() + "' is " +
              (!w.error && S_ISLNK(w.st.st_mode) ? "a symbolic link" : w.error ? "reached through a symbolic link" : "not a folder") +
              "; a project's library tree is a real folder inside it (a link would let a study read wherever it "
              "points): replace it by a folder and run smi-lua libs sync");
}

}  // namespace

ProjectLibraries project_libraries(const fs::path& dir_given) {
  ProjectLibraries p;
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(fs::absolute(dir_given, ec), ec);
  if (fs::is_regular_file(dir / kLockfileName, ec)) {
    p.lockfile = dir / kLockfileName;
    p.lock = read_lockfile(p.lockfile);
    p.tree = lock_tree(*p.lock, p.lockfile);
    p.tree_outside = !tree_inside_project(p.lock->tree);
    if (!p.tree_outside) check_project_tree(dir, p.lock->tree);
  } else if (fs::exists(fs::symlink_status(dir / kTreeName, ec))) {
    check_project_tree(dir, kTreeName);
    p.tree = dir / kTreeName;
  }
  return p;
}

namespace {

/// The version folders of <root>/<name>/: folders named by a version and holding a manifest.
std::vector<fs::path> version_folders(const fs::path& name_dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(name_dir, ec)) {
    if (!e.is_directory(ec) || !fs::is_regular_file(e.path() / kManifestName, ec)) continue;
    try {
      Version::parse(e.path().filename().string());
      out.push_back(e.path());
    } catch (const Error&) {
    }
  }
  return out;
}

/// Chooses one of the side-by-side versions of each library of a tree (appended to `libs`): the
/// version the lockfile pins (the others stay hidden; a pinned version not installed is a
/// problem), else the highest that satisfies every requirement on it from the libraries seen.
void choose_versions(std::map<std::string, std::vector<Library>>& versioned, const ProjectLibraries* project,
                     std::vector<Library>& libs, std::vector<std::string>& problems,
                     std::map<std::string, std::vector<std::string>>& versions) {
  const Lockfile* lock = project && project->lock ? &*project->lock : nullptr;
  // A lockfile pins one version of each library it names and hides the others.
  if (lock)
    for (const LockEntry& e : lock->libs) {
      auto it = versioned.find(e.name);
      bool found = false;
      if (it != versioned.end())
        for (Library& l : it->second)
          if (!found && l.manifest.version.text == e.version) {
            l.source = e.source;
            l.git = GitInfo{};
            l.git.commit = e.commit.size() == 40 ? e.commit : "";
            // A locked library is exactly the files the lockfile records.
            const std::vector<std::string> diff = lock_differences(e.files, l.hash().files);
            if (!diff.empty()) {
              std::string files;
              for (const auto& d : diff) files += "\n    " + d;
              problems.push_back("library " + e.name + " " + e.version + " at " + l.folder.string() +
                                 " is not what " + project->lockfile.string() + " locked:" + files +
                                 "\n    restore it with: smi-lua libs sync");
            }
            libs.push_back(l);
            found = true;
          }
      if (!found)
        problems.push_back(project->lockfile.string() + " pins " + e.name + " " + e.version + ", but " +
                                     (project->tree / e.name / e.version).string() +
                                     " is not installed; run smi-lua libs sync");
    }
  // Without a lock entry: the highest version that satisfies every requirement on it.
  std::map<std::string, std::size_t> pick;  // name -> index in versioned[name]
  for (auto& [name, libs] : versioned) {
    std::sort(libs.begin(), libs.end(), [](const Library& a, const Library& b) {
      return compare(a.manifest.version, b.manifest.version) > 0;
    });
    for (const Library& l : libs) versions[name].push_back(l.manifest.version.text);
    if (lock) continue;
    pick[name] = 0;
  }
  const auto chosen = [&](const std::string& name) { return &versioned[name][pick[name]]; };
  for (int round = 0; round < 20; ++round) {
    bool changed = false;
    for (auto& [name, idx] : pick) {
      std::vector<const Requirement*> on;
      const auto collect = [&](const Library& l) {
        for (const Requirement& r : l.manifest.requires_)
          if (r.name == name) on.push_back(&r);
      };
      for (const Library& l : libs) collect(l);
      for (const auto& [other, j] : pick)
        if (other != name) collect(versioned[other][j]);
      std::size_t best = idx;
      for (std::size_t k = 0; k < versioned[name].size(); ++k) {
        bool ok = true;
        for (const Requirement* r : on) ok = ok && r->accepts(versioned[name][k].manifest.version);
        if (ok) {
          best = k;
          break;
        }
      }
      if (best != idx) {
        idx = best;
        changed = true;
      }
    }
    if (!changed) break;
  }
  for (const auto& [name, idx] : pick) libs.push_back(*chosen(name));
}

}  // namespace

LibrarySet LibrarySet::discover(const std::vector<LibraryRoot>& given, const ProjectLibraries* project) {
  LibrarySet set;
  set.roots_ = given;
  if (project && project->tree_outside) {
    // A tree outside the project is read only when the user names it (--lib, SMI_PATH).
    const fs::path t = lua::resolve_path(project->tree.string());
    bool given_by_user = false;
    for (const LibraryRoot& r : given) given_by_user = given_by_user || lua::resolve_path(r.dir) == t;
    if (!given_by_user) {
      set.tree_problems_.push_back(project->lockfile.string() + " names the library tree '" + project->lock->tree +
                                   "', outside the project folder; a study reads a tree outside its folder only "
                                   "when you give it yourself: --lib " + project->tree.string());
      project = nullptr;
    }
  }
  const Lockfile* lock = project && project->lock ? &*project->lock : nullptr;
  if (project && !project->tree.empty() && !project->tree_outside)
    set.roots_.push_back({project->tree.string(), lock ? "smi-lock.json's tree" : "the project's tree"});
  const auto make = [&](const fs::path& folder, const LibraryRoot& root) {
    Library lib;
    lib.folder = lua::resolve_path(folder.string());
    lib.manifest = read_manifest(lib.folder / kManifestName);
    lib.root = root;
    return lib;
  };
  const auto seen = [&](const fs::path& folder) {
    const fs::path f = lua::resolve_path(folder.string());
    for (const Library& l : set.libs_)
      if (l.folder == f) return true;
    return false;
  };
  // Side-by-side versions, by name; chosen among once every root is read.
  std::map<std::string, std::vector<Library>> versioned;
  for (const LibraryRoot& root : set.roots_) {
    std::error_code ec;
    const fs::path dir(root.dir);
    if (fs::is_regular_file(dir / kManifestName, ec)) {
      // The same folder reached twice (--lib and SMI_PATH naming it) is one library, not a conflict.
      if (!seen(dir)) {
        Library lib = make(dir, root);
        lib.git = git_info(lib.folder);
        set.libs_.push_back(std::move(lib));
      }
      continue;
    }
    if (!fs::is_directory(dir, ec)) continue;  // a missing folder finds nothing (as for plain modules)
    std::vector<fs::path> subs, trees;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      if (!e.is_directory(ec)) continue;
      if (fs::is_regular_file(e.path() / kManifestName, ec)) subs.push_back(e.path());
      else if (!version_folders(e.path()).empty()) trees.push_back(e.path());
    }
    std::sort(subs.begin(), subs.end());  // a stable order, whatever the file system's
    std::sort(trees.begin(), trees.end());
    for (const auto& s : subs)
      if (!seen(s)) {
        Library lib = make(s, root);
        lib.git = git_info(lib.folder);
        set.libs_.push_back(std::move(lib));
      }
    for (const auto& t : trees) {
      std::vector<fs::path> vs = version_folders(t);
      std::sort(vs.begin(), vs.end());
      for (const auto& v : vs) {
        Library lib = make(v, root);
        if (lib.name() != t.filename().string() || lib.manifest.version.text != v.filename().string())
          throw Error("library tree folder '" + v.string() + "' holds " + lib.name() + " " + lib.manifest.version.text +
                      " in its " + kManifestName + ", not " + t.filename().string() + " " + v.filename().string() +
                      ": the folder was changed by hand; remove it and run smi-lua libs sync (or libs add)");
        bool dup = false;
        for (const Library& o : versioned[lib.name()]) dup = dup || o.folder == lib.folder;
        if (!dup) versioned[lib.name()].push_back(std::move(lib));
      }
    }
  }
  choose_versions(versioned, project, set.libs_, set.tree_problems_, set.versions_);
  return set;
}

const Library* LibrarySet::find(const std::string& name) const {
  for (const Library& l : libs_)
    if (l.name() == name) return &l;
  return nullptr;
}

std::string LibrarySet::seen_versions(const std::string& name) const {
  const auto it = versions_.find(name);
  if (it == versions_.end()) return "";
  std::string s;
  for (const auto& v : it->second) s += (s.empty() ? "" : ", ") + v;
  return " (versions of " + name + " in the library tree: " + s + ")";
}

std::vector<std::string> LibrarySet::problems() const {
  std::vector<std::string> out = tree_problems_;
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
                      dep->manifest.version.text + seen_versions(r.name));
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
