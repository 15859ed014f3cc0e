// SPDX-License-Identifier: MIT
#include "platform/eval/sbatch_args.hpp"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <fmt/format.h>
#include <getopt.h>

#include "platform/core/errors.hpp"

namespace smi::eval {
namespace {

using Entry = SbatchTableEntry;
// struct option's has_arg values.
struct Arg {
  static constexpr int No = 0, Required = 1, Optional = 2;
};

// sbatch 22.05.8's option table: the entries of common_options[] in src/common/slurm_opt.c
// (tag slurm-22-05-8-1) that have a name and a set_func or set_func_sbatch, in that order.
// Generated from the source; SPANK plugins may add options at run time, which only makes an
// abbreviation ambiguous for sbatch (it then refuses), never resolves it elsewhere.
constexpr Entry kTable[] = {
    {"account", 'A', Arg::Required},
    {"acctg-freq", 0, Arg::Required},
    {"array", 'a', Arg::Required},
    {"batch", 0, Arg::Required},
    {"begin", 'b', Arg::Required},
    {"bb", 0, Arg::Required},
    {"bbf", 0, Arg::Required},
    {"cluster-constraint", 0, Arg::Required},
    {"chdir", 'D', Arg::Required},
    {"cluster", 0, Arg::Required},
    {"clusters", 'M', Arg::Required},
    {"comment", 0, Arg::Required},
    {"container", 0, Arg::Required},
    {"context", 0, Arg::Required},
    {"contiguous", 0, Arg::No},
    {"constraint", 'C', Arg::Required},
    {"core-spec", 'S', Arg::Required},
    {"cores-per-socket", 0, Arg::Required},
    {"cpu-freq", 0, Arg::Required},
    {"cpus-per-gpu", 0, Arg::Required},
    {"cpus-per-task", 'c', Arg::Required},
    {"deadline", 0, Arg::Required},
    {"delay-boot", 0, Arg::Required},
    {"dependency", 'd', Arg::Required},
    {"distribution", 'm', Arg::Required},
    {"error", 'e', Arg::Required},
    {"exclude", 'x', Arg::Required},
    {"exclusive", 0, Arg::Optional},
    {"export", 0, Arg::Required},
    {"export-file", 0, Arg::Required},
    {"extra-node-info", 'B', Arg::Required},
    {"get-user-env", 0, Arg::Optional},
    {"gid", 0, Arg::Required},
    {"gpu-bind", 0, Arg::Required},
    {"gpu-freq", 0, Arg::Required},
    {"gpus", 'G', Arg::Required},
    {"gpus-per-node", 0, Arg::Required},
    {"gpus-per-socket", 0, Arg::Required},
    {"gpus-per-task", 0, Arg::Required},
    {"gres", 0, Arg::Required},
    {"gres-flags", 0, Arg::Required},
    {"help", 'h', Arg::No},
    {"hint", 0, Arg::Required},
    {"hold", 'H', Arg::No},
    {"ignore-pbs", 0, Arg::No},
    {"input", 'i', Arg::Required},
    {"job-name", 'J', Arg::Required},
    {"kill-on-invalid-dep", 0, Arg::Required},
    {"licenses", 'L', Arg::Required},
    {"mail-type", 0, Arg::Required},
    {"mail-user", 0, Arg::Required},
    {"mcs-label", 0, Arg::Required},
    {"mem", 0, Arg::Required},
    {"mem-bind", 0, Arg::Required},
    {"mem-per-cpu", 0, Arg::Required},
    {"mem-per-gpu", 0, Arg::Required},
    {"mincpus", 0, Arg::Required},
    {"network", 0, Arg::Required},
    {"nice", 0, Arg::Optional},
    {"no-kill", 'k', Arg::Optional},
    {"no-requeue", 0, Arg::No},
    {"nodefile", 'F', Arg::Required},
    {"nodelist", 'w', Arg::Required},
    {"nodes", 'N', Arg::Required},
    {"ntasks", 'n', Arg::Required},
    {"ntasks-per-core", 0, Arg::Required},
    {"ntasks-per-gpu", 0, Arg::Required},
    {"ntasks-per-node", 0, Arg::Required},
    {"ntasks-per-socket", 0, Arg::Required},
    {"ntasks-per-tres", 0, Arg::Required},
    {"open-mode", 0, Arg::Required},
    {"output", 'o', Arg::Required},
    {"overcommit", 'O', Arg::No},
    {"oversubscribe", 's', Arg::No},
    {"parsable", 0, Arg::No},
    {"partition", 'p', Arg::Required},
    {"power", 0, Arg::Required},
    {"prefer", 0, Arg::Required},
    {"priority", 0, Arg::Required},
    {"profile", 0, Arg::Required},
    {"propagate", 0, Arg::Optional},
    {"qos", 'q', Arg::Required},
    {"quiet", 'Q', Arg::No},
    {"reboot", 0, Arg::No},
    {"requeue", 0, Arg::No},
    {"reservation", 0, Arg::Required},
    {"signal", 0, Arg::Required},
    {"sockets-per-node", 0, Arg::Required},
    {"spread-job", 0, Arg::No},
    {"switches", 0, Arg::Required},
    {"tasks-per-node", 0, Arg::Required},
    {"test-only", 0, Arg::No},
    {"thread-spec", 0, Arg::Required},
    {"threads-per-core", 0, Arg::Required},
    {"time", 't', Arg::Required},
    {"time-min", 0, Arg::Required},
    {"tmp", 0, Arg::Required},
    {"uid", 0, Arg::Required},
    {"use-min-nodes", 0, Arg::No},
    {"verbose", 'v', Arg::No},
    {"version", 'V', Arg::No},
    {"usage", 0, Arg::No},
    {"wait", 'W', Arg::No},
    {"wait-all-nodes", 0, Arg::Required},
    {"wckey", 0, Arg::Required},
    {"wrap", 0, Arg::Required},
};

// Options that shape what the job asks of the cluster and nothing else. Not here (refused):
// array, batch, bb, bbf, chdir, cluster(s), container, context, dependency, error, export,
// export-file, get-user-env, gid, uid, help, usage, version, hold, ignore-pbs, input, job-name,
// kill-on-invalid-dep, mail-*, mcs-label, no-requeue, nodefile, open-mode, output, parsable,
// propagate, test-only, wait, wait-all-nodes, wrap, quiet, verbose, begin, deadline, signal,
// priority, nice, reboot, power, profile, acctg-freq, no-kill.
constexpr const char* kAllowed[] = {
    "account", "comment", "constraint", "cluster-constraint", "contiguous", "core-spec", "cores-per-socket",
    "cpu-freq", "cpus-per-gpu", "cpus-per-task", "distribution", "exclude", "exclusive", "extra-node-info",
    "gpu-bind", "gpu-freq", "gpus", "gpus-per-node", "gpus-per-socket", "gpus-per-task", "gres", "gres-flags",
    "hint", "licenses", "mem", "mem-bind", "mem-per-cpu", "mem-per-gpu", "mincpus", "network", "nodelist",
    "nodes", "ntasks", "ntasks-per-core", "ntasks-per-gpu", "ntasks-per-node", "ntasks-per-socket",
    "ntasks-per-tres", "overcommit", "oversubscribe", "partition", "prefer", "qos", "reservation",
    "sockets-per-node", "spread-job", "switches", "thread-spec", "threads-per-core", "time", "time-min", "tmp",
    "use-min-nodes", "wckey"};

const Entry* by_letter(char c) {
  for (const Entry& e : kTable)
    if (e.letter == c) return &e;
  return nullptr;
}

// getopt_long's lookup: an exact name wins; otherwise the options the word abbreviates, and
// more than one is ambiguous (every sbatch option has its own val, so glibc's "same has_arg,
// flag and val" exception never applies).
const Entry* by_name(const std::string& word, const std::string& name) {
  for (const Entry& e : kTable)
    if (name == e.name) return &e;
  std::vector<const Entry*> found;
  for (const Entry& e : kTable)
    if (!name.empty() && std::strncmp(e.name, name.c_str(), name.size()) == 0) found.push_back(&e);
  if (found.empty()) throw InvalidArgument(fmt::format("sbatch argument '{}': sbatch has no option '--{}'", word, name));
  if (found.size() > 1) {
    std::string all;
    for (const Entry* e : found) all += fmt::format("{}--{}", all.empty() ? "" : ", ", e->name);
    throw InvalidArgument(fmt::format("sbatch argument '{}' is ambiguous for sbatch ({}); write the option in full",
                                      word, all));
  }
  return found[0];
}

}  // namespace

std::vector<SbatchOption> parse_sbatch_args(const std::vector<std::string>& args) {
  std::vector<SbatchOption> v;
  // sbatch drops every ":" word before getopt sees the rest (hetjob separators), even one meant
  // as a value: "-c :" would take the next word as -c's value. Refused wherever it is.
  for (const auto& w : args)
    if (w == ":")
      throw InvalidArgument("sbatch argument ':' separates heterogeneous job components; smi-lua submits one array");
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& w = args[i];
    if (w == "--")
      throw InvalidArgument("sbatch argument '--' would end sbatch's options: the next word would become the job script");
    if (w.size() < 2 || w[0] != '-')
      throw InvalidArgument(fmt::format("sbatch argument '{}' is not an option: sbatch would take it as the job script "
                                        "(values go with their option: --gres=gpu:1)", w));
    if (w[1] == '-') {  // --name[=value]
      const auto eq = w.find('=', 2);
      const std::string name = w.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
      const Entry* e = by_name(w, name);
      SbatchOption o{e->name, w, "", false};
      if (eq != std::string::npos) {
        if (e->has_arg == Arg::No)
          throw InvalidArgument(fmt::format("sbatch argument '{}': --{} takes no value", w, e->name));
        o.value = w.substr(eq + 1);
        o.has_value = true;
      } else if (e->has_arg == Arg::Required) {
        if (i + 1 >= args.size())
          throw InvalidArgument(fmt::format("sbatch argument '{}': --{} needs a value", w, e->name));
        o.value = args[++i];
        o.given += " " + o.value;
        o.has_value = true;
      }
      v.push_back(std::move(o));
      continue;
    }
    // -abc: letters, each an option; one that takes a value takes the rest of the word (or,
    // when required and the word ends there, the next word).
    for (std::size_t k = 1; k < w.size(); ++k) {
      const Entry* e = by_letter(w[k]);
      if (!e) throw InvalidArgument(fmt::format("sbatch argument '{}': sbatch has no option '-{}'", w, w[k]));
      SbatchOption o{e->name, w, "", false};
      if (e->has_arg != Arg::No) {
        if (k + 1 < w.size()) {
          o.value = w.substr(k + 1);
          o.has_value = true;
        } else if (e->has_arg == Arg::Required) {
          if (i + 1 >= args.size())
            throw InvalidArgument(fmt::format("sbatch argument '{}': -{} needs a value", w, w[k]));
          o.value = args[++i];
          o.given += " " + o.value;
          o.has_value = true;
        }
        v.push_back(std::move(o));
        break;
      }
      v.push_back(std::move(o));
    }
  }
  return v;
}

const SbatchTableEntry* sbatch_option_table(std::size_t* count) {
  *count = std::size(kTable);
  return kTable;
}

bool sbatch_getopt_reference(const std::vector<std::string>& args, std::vector<std::pair<std::string, std::string>>& out) {
  out.clear();
  for (const auto& a : args)
    if (a == ":") return false;
  std::size_t n = 0;
  const SbatchTableEntry* t = sbatch_option_table(&n);
  std::vector<option> longopts;
  std::string optstring = "+:";
  for (std::size_t i = 0; i < n; ++i) {
    longopts.push_back({t[i].name, t[i].has_arg, nullptr, t[i].letter ? t[i].letter : static_cast<int>(256 + i)});
    if (t[i].letter) {
      optstring += t[i].letter;
      if (t[i].has_arg == 1) optstring += ":";
      if (t[i].has_arg == 2) optstring += "::";
    }
  }
  longopts.push_back({nullptr, 0, nullptr, 0});
  std::vector<std::string> store = args;
  store.insert(store.begin(), "sbatch");
  std::vector<char*> argv;
  for (auto& s : store) argv.push_back(s.data());
  argv.push_back(nullptr);
  opterr = 0;
  optind = 0;  // glibc: full reinitialisation
  const char* last_value = nullptr;
  int c;
  while ((c = getopt_long(static_cast<int>(store.size()), argv.data(), optstring.c_str(), longopts.data(), nullptr)) != -1) {
    if (c == '?' || c == ':') return false;
    std::string name;
    for (std::size_t i = 0; i < n; ++i)
      if ((t[i].letter && c == t[i].letter) || (!t[i].letter && c == static_cast<int>(256 + i))) name = t[i].name;
    out.emplace_back(name, optarg ? optarg : "");
    last_value = optarg;
  }
  if (optind < static_cast<int>(store.size())) return false;  // a bare word: sbatch's script
  if (optind > 1 && std::string(argv[static_cast<std::size_t>(optind - 1)]) == "--" &&
      last_value != argv[static_cast<std::size_t>(optind - 1)])
    return false;  // "--" ended the options
  return true;
}

const char* sbatch_allowed_options() {
  static const std::string s = [] {
    std::string r;
    for (const char* a : kAllowed) r += fmt::format("{}{}", r.empty() ? "" : ", ", a);
    return r;
  }();
  return s.c_str();
}

void check_sbatch_args(const std::vector<std::string>& args) {
  for (const SbatchOption& o : parse_sbatch_args(args)) {
    const bool ok = std::any_of(std::begin(kAllowed), std::end(kAllowed), [&](const char* a) { return o.name == a; });
    if (!ok)
      throw InvalidArgument(fmt::format(
          "executor option sbatch: '{}' is sbatch's --{}, which smi-lua does not pass on (it sets the job's files, "
          "folder, environment, name, array and tracking itself). Allowed: {}",
          o.given, o.name, sbatch_allowed_options()));
  }
}

}  // namespace smi::eval
