// SPDX-License-Identifier: MIT
#pragma once
// The extra sbatch arguments a user may give (--slurm-opt sbatch="..."), read the way sbatch
// itself reads them and then checked against an allow-list. A deny-list of option spellings
// cannot work: sbatch parses with getopt_long, which accepts any unambiguous abbreviation of a
// long option (--outp=, --chd=), short options glued to their value (-o/path) or to each other
// (-Ho/path), a value in the next word, and it drops ":" (the hetjob separator) and stops at the
// first word that is not an option (which then becomes the batch script). So the words are
// parsed with sbatch 22.05's own option table (src/common/slurm_opt.c, the entries sbatch
// registers), each is resolved to its canonical option, and only options that shape resources
// (nodes, memory per CPU, GPUs, constraints, ...) pass. Anything that names a file, a folder, an
// environment, an identity, a dependency or changes how the job is tracked is refused, as are
// unknown options, ambiguous abbreviations, ":" , "--" and bare words.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace smi::eval {

/// One entry of sbatch's option table: long name, short letter (0 = none), argument kind as in
/// struct option (0 no_argument, 1 required_argument, 2 optional_argument).
struct SbatchTableEntry {
  const char* name;
  char letter;
  int has_arg;
};

/// sbatch 22.05.8's options (the fuzz target and the tests rebuild getopt_long's table from it).
const SbatchTableEntry* sbatch_option_table(std::size_t* count);

/// One option as sbatch's getopt_long would see it.
struct SbatchOption {
  std::string name;        // canonical long name ("output"), or the short letter's long name
  std::string given;       // the word(s) as written, for messages
  std::string value;       // the argument, if any
  bool has_value = false;
};

/// Parses `args` as sbatch 22.05 does (getopt_long, optstring "+..."). Throws InvalidArgument
/// naming the word: unknown option, ambiguous abbreviation, missing or unexpected value, a
/// word that is not an option (sbatch would take it as the script), "--", ":".
std::vector<SbatchOption> parse_sbatch_args(const std::vector<std::string>& args);

/// Parses, then refuses every option not on the allow-list, naming the word, the option it
/// resolves to and the allowed ones.
void check_sbatch_args(const std::vector<std::string>& args);

/// The reference reading: glibc's getopt_long over the same table, called as sbatch 22.05 calls
/// it ("+" optstring, ":" words removed first). False where sbatch would not read every word
/// as an option (an error, a ":" word, "--", a word left over that would become the script);
/// else the canonical names with their values. The oracle of the tests and the fuzz target
/// (bench/fuzz_sbatch_args.cpp); not used to decide anything (getopt_long keeps global state).
bool sbatch_getopt_reference(const std::vector<std::string>& args,
                             std::vector<std::pair<std::string, std::string>>& out);

/// The allowed canonical names, comma-separated (messages, docs).
const char* sbatch_allowed_options();

}  // namespace smi::eval
