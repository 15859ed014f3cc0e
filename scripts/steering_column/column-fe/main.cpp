// SPDX-License-Identifier: MIT
// smi-column-fe DECK -o RESULTS: the open steering-column model (docs/spec/steering-column.md).
// smi-column-fe --batch POINTS.csv --base DECK -o OUT.csv [--threads N]: many points in one process
// (batch.hpp), for screening and other large samples.
// Exit 0 on success; 1 with the message on stderr for a bad deck or a failed solution (no
// results file is left behind); 2 for a usage error.
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <cstdlib>
#include <string>

#include "batch.hpp"
#include "deck.hpp"
#include "solve.hpp"

namespace {

const char* kUsage =
    "usage: smi-column-fe DECK -o RESULTS\n"
    "       smi-column-fe --batch POINTS.csv --base DECK -o OUT.csv [--threads N]\n"
    "       smi-column-fe --help | --version\n"
    "\n"
    "Solves the open steering-column analog of Son et al. (2020): a 3-D Euler-Bernoulli frame\n"
    "(jacket, shaft, brackets, bushes, wheel) with consistent mass, for its 10 lowest modes, and\n"
    "labels paper modes 1 (vertical), 2 (lateral), 3 (torsion) and 4 (wheel pitch).\n"
    "\n"
    "DECK     'key = value' lines, '#' comments: airbag_model = rigid|spring, the 46 inputs,\n"
    "         airbag_stiffness (spring only), optional mesh_refinement = 1..8.\n"
    "RESULTS  .f06-like text file: eigenvalue table, mode labels, PAPER MODE lines.\n"
    "--batch  POINTS.csv: a header of input names, one row of values per point; inputs a row\n"
    "         does not name (and airbag_model, mesh_refinement) come from the --base deck.\n"
    "         OUT.csv: point,mode1_hz,mode2_hz,mode3_hz,mode4_hz (paper modes, nan if absent).\n"
    "Units: N, mm, tonne, s. Specification: docs/spec/steering-column.md.\n";

int usage_error(const std::string& what) {
  std::cerr << "smi-column-fe: " << what << "\n" << kUsage;
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string deck, out, batch, base;
  int threads = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (a == "--version") {
      std::cout << "smi-column-fe " << COLUMN_FE_VERSION << "\n";
      return 0;
    }
    if (a == "--batch" || a == "--base" || a == "--threads") {
      if (i + 1 >= argc) return usage_error(a + " needs a value");
      std::string& dst = a == "--batch" ? batch : base;
      if (a == "--threads") {
        const std::string v = argv[++i];
        char* end = nullptr;
        const long t = std::strtol(v.c_str(), &end, 10);
        if (v.empty() || *end != '\0' || t < 1 || t > 64) return usage_error("--threads needs an integer from 1 to 64, got '" + v + "'");
        threads = static_cast<int>(t);
        continue;
      }
      if (!dst.empty()) return usage_error(a + " given twice");
      dst = argv[++i];
      continue;
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
  if (!batch.empty()) {
    if (!deck.empty()) return usage_error("give either a DECK or --batch POINTS.csv, not both");
    if (base.empty()) return usage_error("--batch needs --base DECK (airbag_model and the inputs the points do not set)");
  } else {
    if (!base.empty()) return usage_error("--base is only used with --batch POINTS.csv");
    if (threads != 1) return usage_error("--threads is only used with --batch POINTS.csv");
    if (deck.empty()) return usage_error("no deck given");
  }
  if (out.empty()) return usage_error(batch.empty() ? "no results file given (-o RESULTS)" : "no output file given (-o OUT.csv)");
  try {
    // Everything is read and checked before the output is touched.
    std::ostringstream text;
    if (batch.empty()) {
      cfe::write_results(text, cfe::run_model(cfe::read_deck(deck)));
    } else {
      std::ifstream f(batch, std::ios::binary);
      if (!f) throw cfe::DeckError(batch + ": cannot open the points file (check the path and permissions)");
      std::ostringstream ss;
      ss << f.rdbuf();
      cfe::run_batch(cfe::read_deck(base), cfe::parse_points(ss.str(), batch), batch, text, threads);
    }
    // Write beside the target and rename, so a reader never sees a half-written file.
    const std::string tmp = out + ".part";
    {
      std::ofstream f(tmp, std::ios::binary);
      if (!f) throw std::runtime_error(out + ": cannot write the results file (check the directory)");
      f << text.str();
      if (!f.flush()) throw std::runtime_error(out + ": write failed");
    }
    std::filesystem::rename(tmp, out);
  } catch (const std::exception& e) {
    std::cerr << "smi-column-fe: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
