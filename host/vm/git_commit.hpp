// SPDX-License-Identifier: MIT
#pragma once
// The git commit a folder is checked out at, read from the .git files directly (HEAD, loose
// refs, packed-refs, "gitdir:" files of worktrees and submodules): no git program is run, so
// this works inside the sandbox and on machines without git.
#include <filesystem>
#include <string>

namespace smi::vm {

struct GitInfo {
  std::string commit;                // 40 hex digits; empty when not a checkout or no commit yet
  std::string branch;                // "main"; empty when HEAD is detached
  std::filesystem::path repo_root;   // the folder holding .git (the library folder or a parent)
};

/// Looks for .git in `folder` and its parents. Never throws: unreadable or odd repositories
/// give an empty commit. Everything read stays inside the folder holding .git (a "gitdir:"
/// file, commondir or symlink pointing elsewhere is not followed, so a linked worktree or a
/// submodule whose git dir lives outside its checkout reports no commit), only regular files
/// are read, and each at most 4 KiB (packed-refs 64 MiB).
GitInfo git_info(const std::filesystem::path& folder);

}  // namespace smi::vm
