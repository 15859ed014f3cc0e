// SPDX-License-Identifier: MIT
#include "vm/library_tree.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/errors.hpp"
#include "platform/core/path_walk.hpp"
#include "vm/manifest.hpp"
#include "vm/semver.hpp"

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

/// One plain path component: not empty, not "." or "..", no separator or NUL. Redundant after
/// the name and version grammars, and kept so that no later change of a grammar makes a path.
bool one_component(const std::string& s) {
  return !s.empty() && s != "." && s != ".." && s.find_first_of(std::string("/\\\0", 3)) == std::string::npos;
}

}  // namespace

fs::path library_dir(const fs::path& tree, const std::string& name, const std::string& version) {
  if (!valid_library_name(name) || !one_component(name))
    throw Error("'" + visible_text(name) + "' is not a library name (letters, digits and '_', not starting with a digit), "
                "so it names no folder of the library tree");
  try {
    const Version v = Version::parse(version);
    (void)v;
  } catch (const Error& e) {
    throw Error("library " + name + ": " + e.what() + "; a version names a folder of the library tree, so it must be "
                "MAJOR.MINOR.PATCH[-PRERELEASE][+BUILD] exactly");
  }
  if (!one_component(version)) throw Error("library " + name + ": version '" + visible_text(version) + "' is not one folder name");
  return tree / name / version;
}

LibraryTree LibraryTree::open(const fs::path& tree, bool create) {
  LibraryTree t;
  t.given_ = tree;
  const std::string abs = fs::absolute(tree).lexically_normal().string();
  pathwalk::Walk w = pathwalk::walk(abs, false);
  if (w.error == ENOENT && create) {  // missing parents: made without following a link
    if (!pathwalk::make_dirs_nofollow(abs))
      throw Error("cannot create the library tree '" + tree.string() + "': " + std::strerror(errno));
    w = pathwalk::walk(abs, false);
  }
  if (w.error)
    throw Error("cannot reach the library tree '" + tree.string() + "' (" + w.where + "): " + std::strerror(w.error));
  if (w.exists && S_ISLNK(w.st.st_mode))
    throw Error("the library tree '" + tree.string() + "' is a symbolic link; a library tree is a real folder (a link "
                "would install and remove libraries wherever it points): replace it by a folder and run smi-lua libs sync");
  if (w.exists && !S_ISDIR(w.st.st_mode))
    throw Error("the library tree '" + tree.string() + "' is not a folder; move it away and run smi-lua libs sync");
  if (!w.exists && !create) return t;
  if (!w.exists) {
    const pathwalk::Fd made = pathwalk::make_dirs_nofollow(w.canonical());
    if (!made) throw Error("cannot create the library tree '" + tree.string() + "': " + std::strerror(errno));
  }
  t.canonical_ = w.canonical();
  return t;
}

fs::path LibraryTree::target(const std::string& name, const std::string& version) const {
  const fs::path p = library_dir(canonical_, name, version);
  const pathwalk::Walk w = pathwalk::walk(p.string(), false);
  const std::string name_dir = (canonical_ / name).string();
  const std::string why = "; a library tree holds only real folders: remove it and run smi-lua libs sync";
  if (w.error == ENOENT) return p;  // the name folder does not exist yet
  if (w.error == ENOTDIR || (!w.error && w.dir_path != name_dir))
    throw Error("'" + name_dir + "' in the library tree is a symbolic link or not a folder" + why);
  if (w.error) throw Error("cannot reach '" + p.string() + "': " + std::strerror(w.error));
  if (w.exists && !S_ISDIR(w.st.st_mode))
    throw Error("'" + p.string() + "' in the library tree is a symbolic link or not a folder" + why);
  return p;
}

bool LibraryTree::has(const std::string& name, const std::string& version) const {
  if (canonical_.empty()) return false;
  const fs::path p = target(name, version);
  struct stat st;
  return ::lstat(p.c_str(), &st) == 0;
}

void LibraryTree::install(const fs::path& staged, const std::string& name, const std::string& version) const {
  const fs::path p = target(name, version);
  if (has(name, version)) throw Error("cannot install into '" + p.string() + "': it exists already");
  const pathwalk::Fd dir = pathwalk::make_dirs_nofollow((canonical_ / name).string());
  if (!dir) throw Error("cannot create '" + (canonical_ / name).string() + "': " + std::strerror(errno));
  if (::renameat(AT_FDCWD, staged.c_str(), dir.get(), version.c_str()) != 0)
    throw Error("cannot install into '" + p.string() + "': " + std::strerror(errno));
}

void LibraryTree::remove(const std::string& name, const std::string& version) const {
  const fs::path p = target(name, version);
  const pathwalk::Walk w = pathwalk::walk(p.string(), false);
  if (w.error == ENOENT || (!w.error && !w.exists)) return;
  if (w.error || !pathwalk::remove_tree_at(w.dir.get(), w.leaf))
    throw Error("cannot remove '" + p.string() + "': " + std::strerror(w.error ? w.error : errno));
  const pathwalk::Walk n = pathwalk::walk((canonical_ / name).string(), false);
  if (!n.error && n.exists && S_ISDIR(n.st.st_mode)) ::unlinkat(n.dir.get(), n.leaf.c_str(), AT_REMOVEDIR);
}

}  // namespace smi::vm
