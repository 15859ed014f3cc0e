// column-fe DECK -o RESULTS: the open steering-column model (shared/spec/steering-column.md).
// Exit 0 on success; 1 with the message on stderr for a bad deck or a failed solution (no
// results file is left behind); 2 for a usage error.
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "deck.hpp"
#include "solve.hpp"

namespace {

const char* kUsage =
    "usage: column-fe DECK -o RESULTS\n"
    "       column-fe --help | --version\n"
    "\n"
    "Solves the open steering-column analog of Son et al. (2020): a 3-D Euler-Bernoulli frame\n"
    "(jacket, shaft, brackets, bushes, wheel) with consistent mass, for its 10 lowest modes, and\n"
    "labels paper modes 1 (vertical), 2 (lateral), 3 (torsion) and 4 (wheel pitch).\n"
    "\n"
    "DECK     'key = value' lines, '#' comments: airbag_model = rigid|spring, the 46 inputs,\n"
    "         airbag_stiffness (spring only), optional mesh_refinement = 1..8.\n"
    "RESULTS  .f06-like text file: eigenvalue table, mode labels, PAPER MODE lines.\n"
    "Units: N, mm, tonne, s. Specification: shared/spec/steering-column.md.\n";

int usage_error(const std::string& what) {
  std::cerr << "column-fe: " << what << "\n" << kUsage;
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string deck, out;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (a == "--version") {
      std::cout << "column-fe " << COLUMN_FE_VERSION << "\n";
      return 0;
    }
    if (a == "-o") {
      if (i + 1 >= argc) return usage_error("-o needs a file name");
      if (!out.empty()) return usage_error("-o given twice");
      out = argv[++i];
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "'");
    } else if (deck.empty()) {
      deck = a;
    } else {
      return usage_error("more than one deck given ('" + deck + "', '" + a + "')");
    }
  }
  if (deck.empty()) return usage_error("no deck given");
  if (out.empty()) return usage_error("no results file given (-o RESULTS)");
  try {
    const cfe::Results r = cfe::run_model(cfe::read_deck(deck));
    // Write beside the target and rename, so a reader never sees a half-written file.
    const std::string tmp = out + ".part";
    {
      std::ofstream f(tmp, std::ios::binary);
      if (!f) throw std::runtime_error(out + ": cannot write the results file (check the directory)");
      cfe::write_results(f, r);
      if (!f.flush()) throw std::runtime_error(out + ": write failed");
    }
    std::filesystem::rename(tmp, out);
  } catch (const std::exception& e) {
    std::cerr << "column-fe: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
