// smi-lua [options] [script [args]]: a minimal front end (the full CLI of issue 2 replaces it).
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "vm/runtime.hpp"

int main(int argc, char** argv) {
  try {
    smi::vm::Config cfg;
    smi::vm::Runtime rt(cfg);
    int i = 1;
    for (; i < argc; ++i) {
      if (std::strcmp(argv[i], "-e") == 0 && i + 1 < argc) {
        if (!rt.run_string(argv[++i], "=(command line)")) return 1;
      } else if (std::strcmp(argv[i], "--quiet") == 0) {
      } else {
        break;
      }
    }
    if (i < argc) {
      std::vector<std::string> args(argv + i + 1, argv + argc);
      if (!rt.run_file(argv[i], args)) return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "smi-lua: %s\n", e.what());
    return 1;
  }
}
