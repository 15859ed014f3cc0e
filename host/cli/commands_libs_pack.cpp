// SPDX-License-Identifier: MIT
// smi-lua libs pack DIR [FILE]: a release of the library in DIR as <name>-<version>.tar.gz (or
// FILE): every file under one folder <name>-<version>/, plus smi-pack.sha256 (sha256sum's
// format, so `sha256sum -c` checks it too), which `libs add` verifies member by member. The
// archive is byte-reproducible: the same files give the same .tar.gz.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

#include "cli/commands.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/sha256.hpp"
#include "vm/library_sources.hpp"
#include "vm/tar_gz.hpp"

namespace smi::cli {
namespace fs = std::filesystem;

int libs_pack(const Args&, const std::vector<std::string>& args) {
  if (args.empty() || args.size() > 2) {
    std::fprintf(stderr, "usage: smi-lua libs pack DIR [FILE]   (FILE defaults to ./<name>-<version>.tar.gz)\n");
    return 2;
  }
  const fs::path dir = args[0];
  const vm::Manifest m = vm::read_library_folder(dir);
  std::error_code ec;
  const std::string top = m.name + "-" + m.version.text;
  const fs::path out = args.size() == 2 ? fs::path(args[1]) : fs::path(top + ".tar.gz");
  const fs::path out_abs = fs::weakly_canonical(fs::absolute(out), ec);

  // The files as `libs add` installs them: no .git, no smi-out outputs, no links.
  std::vector<fs::path> dirs, files;
  fs::recursive_directory_iterator it(dir, fs::directory_options::none, ec), end;
  if (ec) throw Error("cannot list '" + dir.string() + "': " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) throw Error("cannot list '" + dir.string() + "': " + ec.message());
    const fs::path rel = it->path().lexically_relative(dir);
    const std::string leaf = it->path().filename().string();
    const auto st = it->symlink_status(ec);
    if (leaf == ".git" || (leaf == "smi-out" && fs::is_directory(st))) {
      if (fs::is_directory(st)) it.disable_recursion_pending();
      continue;
    }
    if (rel == vm::kPackChecksums) continue;  // written fresh below
    if (fs::is_symlink(st))
      throw Error("cannot pack '" + rel.generic_string() + "': it is a symbolic link, and a pack holds only files and "
                  "folders (replace the link by the file)");
    if (fs::is_directory(st)) dirs.push_back(rel);
    else if (fs::is_regular_file(st)) {
      if (fs::weakly_canonical(fs::absolute(it->path()), ec) == out_abs) continue;  // the archive being written
      files.push_back(rel);
    } else {
      throw Error("cannot pack '" + rel.generic_string() + "': neither a file nor a folder");
    }
  }
  std::sort(dirs.begin(), dirs.end());
  std::sort(files.begin(), files.end());
  std::vector<vm::TarMember> members;
  members.push_back({top, true, false, ""});
  for (const auto& d : dirs) members.push_back({top + "/" + d.generic_string(), true, false, ""});
  std::string sums;
  for (const auto& f : files) {
    std::ifstream in(dir / f, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    if (!in && !in.eof()) throw Error("cannot read '" + (dir / f).string() + "'");
    struct stat st {};
    ::stat((dir / f).c_str(), &st);
    vm::TarMember t{top + "/" + f.generic_string(), false, (st.st_mode & S_IXUSR) != 0, ss.str()};
    sums += sha256_hex(t.data) + "  " + f.generic_string() + "\n";
    members.push_back(std::move(t));
  }
  members.push_back({top + "/" + vm::kPackChecksums, false, false, sums});
  vm::write_tar_gz(out, members);
  std::printf("packed %s %s: %zu files and %s into %s (SHA-256 %s)\n", m.name.c_str(), m.version.text.c_str(),
              files.size(), vm::kPackChecksums, out.string().c_str(), sha256_file(out.string()).c_str());
  std::printf("teams add it with: smi-lua libs add %s\n", out.string().c_str());
  return 0;
}

}  // namespace smi::cli
