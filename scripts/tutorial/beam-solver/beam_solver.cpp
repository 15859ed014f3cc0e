// SPDX-License-Identifier: MIT
// smi-beam-solver DECK: the tutorial's stand-in for a CAE solver (docs/tutorial.md). It reads a
// deck of "key = value" lines ('#' starts a comment) holding E (MPa), h (mm), b (mm), L (mm)
// and rho (t/mm^3) of a cantilever, and writes beam.out in the current folder:
//     freq_hz = <first bending frequency>
// from Euler-Bernoulli beam theory, f1 = (1.875104^2 / 2 pi) sqrt(E I / (rho A L^4)), I = b h^3/12,
// A = b h. A missing or non-positive value is an error (exit status 2, message on stderr), as a
// real solver rejects a bad deck.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: smi-beam-solver DECK\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in) {
    std::fprintf(stderr, "smi-beam-solver: cannot read %s\n", argv[1]);
    return 2;
  }
  std::map<std::string, double> v;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (const auto c = line.find('#'); c != std::string::npos) line.erase(c);
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    std::string key = line.substr(0, eq);
    key.erase(0, key.find_first_not_of(" \t"));
    key.erase(key.find_last_not_of(" \t") + 1);
    char* end = nullptr;
    const double x = std::strtod(line.c_str() + eq + 1, &end);
    if (end == line.c_str() + eq + 1) {
      std::fprintf(stderr, "smi-beam-solver: %s:%d: '%s' is not a number\n", argv[1], n, line.c_str() + eq + 1);
      return 2;
    }
    v[key] = x;
  }
  for (const char* k : {"E", "h", "b", "L", "rho"})
    if (!(v[k] > 0)) {
      std::fprintf(stderr, "smi-beam-solver: %s: %s must be given and positive\n", argv[1], k);
      return 2;
    }
  const double pi = std::acos(-1.0), lambda = 1.875104068711961;
  const double I = v["b"] * std::pow(v["h"], 3) / 12, A = v["b"] * v["h"];
  const double f = lambda * lambda / (2 * pi) * std::sqrt(v["E"] * I / (v["rho"] * A * std::pow(v["L"], 4)));
  std::FILE* out = std::fopen("beam.out", "w");
  if (!out) {
    std::fprintf(stderr, "smi-beam-solver: cannot write beam.out\n");
    return 2;
  }
  std::fprintf(out, "# smi-beam-solver 1.0\nfreq_hz = %.10g\n", f);
  return std::fclose(out) == 0 ? 0 : 2;
}
