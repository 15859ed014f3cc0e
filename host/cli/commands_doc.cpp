// smi-lua doc [NAME | WORD]      the reference text of NAME, the entries mentioning WORD, or the
//                                list of modules (the same text help() prints in the REPL)
// smi-lua doc --html DIR         a browsable, self-contained reference in DIR (index.html, one
//                                page per module, search in plain JavaScript, the examples with
//                                the output they printed when the reference was made)
// smi-lua doc --check            runs every example and fails (status 1) when one fails or when
//                                a public function, method or module has no doc text
// smi-lua doc --missing          lists the public names without a doc text (status 1 if any)
// The work is done by stdlib/smi/doc.lua and smi/doc/cli.lua in a sandboxed runtime that may
// write only DIR (and the examples' output folder).
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
    "usage: smi-lua doc [NAME|WORD] | doc --html DIR | doc --check | doc --missing  [--out DIR] [--stdlib-dir DIR]\n";
}

int cmd_doc(const Args& first, int argc, char** argv) {
  app::Config cfg = first.cfg;
  std::vector<std::string> words;
  std::string html_dir;
  for (int i = first.script_index + 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&](const char* what) -> std::string {
      if (i + 1 >= argc) throw Error(std::string("doc: ") + s + " needs " + what);
      return argv[++i];
    };
    if (s == "--html") html_dir = value("a folder");
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
    words.insert(words.begin(), {"--html", html_dir});
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
