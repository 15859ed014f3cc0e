// SPDX-License-Identifier: MIT
// smi-lua doc [NAME | WORD]      the reference text of NAME, the entries mentioning WORD, or the
//                                list of modules (the same text help() prints in the REPL)
// smi-lua doc --html DIR         a browsable, self-contained reference in DIR (index.html, one
//                                page per module, search in plain JavaScript, the examples with
//                                the output they printed when the reference was made), and the
//                                guides (docs/*.md) rendered in DIR/guides/: from --guides FOLDER,
//                                else the installed ones (<prefix>/share/doc/smi-lua beside bin/)
// smi-lua doc --check            runs every example and fails (status 1) when one fails or when
//                                a public function, method or module has no doc text
// smi-lua doc --missing          lists the public names without a doc text (status 1 if any)
// The work is done by stdlib/smi/doc.lua and smi/doc/cli.lua in a sandboxed runtime that may
// write only DIR (and the examples' output folder).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/runtime.hpp"
#include "cli/bindings_root.hpp"
#include "cli/commands.hpp"
#include "platform/core/errors.hpp"

namespace smi::cli {
namespace fs = std::filesystem;

namespace {
const char* const kDocUsage =
    "usage: smi-lua doc [NAME|WORD] | doc --html DIR [--guides FOLDER] | doc --check | doc --missing  [--out DIR] "
    "[--stdlib-dir DIR]\n";

/// The installed guides: <prefix>/share/doc/smi-lua when the program runs from <prefix>/bin.
fs::path installed_guides() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const fs::path dir = exe.parent_path().parent_path() / "share" / "doc" / "smi-lua";
  return fs::is_directory(dir, ec) ? dir : fs::path();
}

/// The guides' *.md files of `folder`, sorted by name.
std::vector<std::string> guide_files(const fs::path& folder) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec))
    if (e.is_regular_file(ec) && e.path().extension() == ".md") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}
}

int cmd_doc(const Args& first, int argc, char** argv) {
  app::Config cfg = first.cfg;
  std::vector<std::string> words;
  std::string html_dir;
  fs::path guides;
  for (int i = first.script_index + 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&](const char* what) -> std::string {
      if (i + 1 >= argc) throw Error(std::string("doc: ") + s + " needs " + what);
      return argv[++i];
    };
    if (s == "--html") html_dir = value("a folder");
    else if (s == "--guides") guides = value("a folder of guides (docs/*.md)");
    else if (s == "--out") cfg.out_dir = value("a folder");
    else if (s == "--stdlib-dir") cfg.stdlib_dir = value("a folder");
    else if (s == "--help" || s == "-h") {
      std::fputs(kDocUsage, stdout);
      return 0;
    } else if (s.size() > 2 && s.rfind("--", 0) == 0 && s != "--check" && s != "--missing") {
      std::fprintf(stderr, "smi-lua doc: unknown option '%s'\n%s", s.c_str(), kDocUsage);
      return 2;
    } else {
      words.push_back(s);
    }
  }
  if (!html_dir.empty()) {
    fs::create_directories(html_dir);
    cfg.allow_write.push_back(html_dir);
    if (cfg.out_dir.empty()) cfg.out_dir = (fs::path(html_dir) / "example-files").string();
    if (guides.empty()) guides = installed_guides();
    std::vector<std::string> g;
    if (!guides.empty()) {
      if (!fs::is_directory(guides)) throw Error("--guides " + guides.string() + ": not a folder");
      fs::create_directories(fs::path(html_dir) / "guides");
      cfg.allow_read.push_back(guides.string());
      for (const auto& f : guide_files(guides)) g.insert(g.end(), {"--guide", f});
    }
    words.insert(words.begin(), {"--html", html_dir});
    words.insert(words.begin() + 2, g.begin(), g.end());
  }
  if (cfg.out_dir.empty()) cfg.out_dir = (fs::path("smi-out") / "doc").string();
  cfg.script.clear();
  // The examples of smi.model.command/batch use /bin/sh as their solver (bindings/eval/doc.cpp).
  cfg.allow_exec.push_back("/bin/sh");
  app::Runtime rt(cfg, all_bindings());
  lua_State* L = rt.state();
  // require("smi.doc.cli").main(words)
  lua_getglobal(L, "require");
  lua_pushliteral(L, "smi.doc.cli");
  if (rt.docall(1, 1) != LUA_OK) return rt.report(LUA_ERRRUN);
  lua_getfield(L, -1, "main");
  lua_remove(L, -2);
  lua_createtable(L, static_cast<int>(words.size()), 0);
  for (std::size_t i = 0; i < words.size(); ++i) {
    lua_pushstring(L, words[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  if (rt.docall(1, 1) != LUA_OK) return rt.report(LUA_ERRRUN);
  if (rt.exit_requested()) return 0;
  const int code = lua_isinteger(L, -1) ? static_cast<int>(lua_tointeger(L, -1)) : 0;
  lua_pop(L, 1);
  return code;
}

}  // namespace smi::cli
