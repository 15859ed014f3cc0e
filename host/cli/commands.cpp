// SPDX-License-Identifier: MIT
#include "cli/commands.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace smi::cli {

bool is_command(const std::string& w) { return w == "libs" || w == "new-lib" || w == "test" || w == "verify" || w == "doc" || w == "report"; }

vm::LibrarySet current_libraries(const Args& a) {
  const vm::ProjectLibraries project = vm::project_libraries(std::filesystem::current_path());
  return vm::LibrarySet::discover(vm::library_roots(a.cfg.lib_dirs, a.ignore_env ? nullptr : std::getenv("SMI_PATH")),
                                  &project);
}

int run_command(const Args& first, int argc, char** argv) {
  // Options may follow the command word: move them in front of it and parse once more, so
  // every option means what it means for a study. Whether an option takes a value is asked of
  // the parser itself (it reports "needs an argument" for a valued option given alone).
  const int at = first.script_index;
  const std::string word = argv[at];
  if (word == "doc") {  // doc has options of its own (--html DIR): it reads its words itself
    try {
      return cmd_doc(first, argc, argv);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "smi-lua doc: %s\n", e.what());
      return 1;
    }
  }
  std::vector<std::string> opts, pos;
  std::string into;
  bool check = false;
  for (int i = at + 1; i < argc; ++i) {
    const std::string s = argv[i];
    if (word == "libs" && s == "--check") {  // options of libs alone (libs_install.cpp)
      check = true;
      continue;
    }
    if (word == "libs" && (s == "--into" || s.rfind("--into=", 0) == 0)) {
      if (s != "--into") into = s.substr(7);
      else if (i + 1 < argc) into = argv[++i];
      if (into.empty()) {
        std::fprintf(stderr, "smi-lua libs: --into needs a folder (the library tree, default ./smi-libs)\n");
        return 2;
      }
      continue;
    }
    if (s == "--") {
      for (++i; i < argc; ++i) pos.push_back(argv[i]);
      break;
    }
    if ((word == "verify" && s == "--json") || (word == "report" && s == "--pdf")) {  // the command's own option
      pos.push_back(s);
    } else if (s.size() > 1 && s[0] == '-') {
      char* probe[] = {argv[0], const_cast<char*>(s.c_str()), nullptr};
      const Args t = parse(2, probe);
      opts.push_back(s);
      if (t.error.find("needs an argument") != std::string::npos && i + 1 < argc) opts.push_back(argv[++i]);
    } else {
      pos.push_back(s);
    }
  }
  std::vector<std::string> words(argv, argv + at);
  words.insert(words.end(), opts.begin(), opts.end());
  words.push_back(word);
  std::vector<char*> av;
  for (auto& w : words) av.push_back(w.data());
  av.push_back(nullptr);
  Args a = parse(static_cast<int>(words.size()), av.data());
  a.libs_into = into;
  a.libs_check = check;
  if (!a.error.empty()) {
    std::fprintf(stderr, "smi-lua %s: %s\n", word.c_str(), a.error.c_str());
    return 2;
  }
  try {
    if (word == "libs") return cmd_libs(a, pos);
    if (word == "new-lib") return cmd_new_lib(a, pos);
    if (word == "test") return cmd_test(a, pos, argv[0]);
    if (word == "report") return cmd_report(a, pos);
    return cmd_verify(a, pos);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "smi-lua %s: %s\n", word.c_str(), e.what());
    return 1;
  }
}

}  // namespace smi::cli
