// SPDX-License-Identifier: MIT
// libFuzzer target over the sbatch argument parser (host/platform/eval/sbatch_args.cpp), with
// glibc's getopt_long as oracle (sbatch_getopt_reference in host/platform/eval/sbatch_args.cpp). Built and run by
// bench/run_fuzz_sbatch_args.sh (clang, -fsanitize=fuzzer,address,undefined); not part of the
// CMake build. An input is a list of words separated by '\n'. Checked on every input:
//  1. no crash, leak, overflow or undefined behaviour (the sanitizers);
//  2. parse_sbatch_args refuses exactly where sbatch would not read every word as an option,
//     and otherwise finds the options getopt_long finds, with the same values, in order;
//  3. whatever check_sbatch_args lets through resolves, for getopt_long too, only to options
//     of the allow-list.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "platform/core/errors.hpp"
#include "platform/eval/sbatch_args.hpp"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  std::vector<std::string> words(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') words.emplace_back();
    else if (data[i] == 0) return 0;  // argv words cannot hold NUL
    else words.back() += static_cast<char>(data[i]);
  }
  std::vector<std::pair<std::string, std::string>> want;
  const bool ok = smi::eval::sbatch_getopt_reference(words, want);
  std::vector<std::pair<std::string, std::string>> got;
  bool parsed = true;
  try {
    for (const auto& o : smi::eval::parse_sbatch_args(words)) got.emplace_back(o.name, o.value);
  } catch (const smi::InvalidArgument&) {
    parsed = false;
  }
  if (parsed != ok || (ok && got != want)) {
    std::fprintf(stderr, "disagreement with getopt_long: oracle %s, parser %s\n", ok ? "parsed" : "refused",
                 parsed ? "parsed" : "refused");
    std::abort();
  }
  bool allowed = true;
  try {
    smi::eval::check_sbatch_args(words);
  } catch (const smi::InvalidArgument&) {
    allowed = false;
  }
  if (allowed) {
    const std::string list = std::string(", ") + smi::eval::sbatch_allowed_options() + ",";
    for (const auto& [name, value] : want)
      if (list.find(", " + name + ",") == std::string::npos) {
        std::fprintf(stderr, "allowed a word that getopt_long reads as --%s\n", name.c_str());
        std::abort();
      }
  }
  return 0;
}
