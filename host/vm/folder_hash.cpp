#include "vm/folder_hash.hpp"

#include "core/errors.hpp"
#include "core/sha256.hpp"  // the evaluation store's SHA-256 (one implementation in the tree)

namespace smi::vm {
namespace fs = std::filesystem;

std::string combine_file_hashes(const std::map<std::string, std::string>& files) {
  Sha256 h;
  h.field("smi-lib-folder-v1");
  for (const auto& [rel, digest] : files) h.field(rel).field(digest);  // std::map: sorted by path
  return "sha256:" + h.hex();
}

FolderHash hash_folder(const fs::path& folder) {
  FolderHash out;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw Error("library folder '" + folder.string() + "' is not a folder");
  fs::recursive_directory_iterator it(folder, fs::directory_options::none, ec), end;
  if (ec) throw Error("cannot list library folder '" + folder.string() + "': " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) throw Error("cannot list library folder '" + folder.string() + "': " + ec.message());
    const fs::path& p = it->path();
    const std::string leaf = p.filename().string();
    if (it->is_directory(ec) && (leaf == ".git" || leaf == "smi-out")) {
      it.disable_recursion_pending();
      continue;
    }
    if (leaf == ".git") continue;  // a worktree's or submodule's "gitdir:" file
    if (!it->is_regular_file(ec)) continue;
    out.files[p.lexically_relative(folder).generic_string()] = sha256_file(p.string());
  }
  out.digest = combine_file_hashes(out.files);
  return out;
}

}  // namespace smi::vm
