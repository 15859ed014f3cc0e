// SPDX-License-Identifier: MIT
// smi-lua verify RESULTS.json [--json]: re-checks everything a study's results depend on, as its
// results file recorded it under "provenance": the study script, every file the run
// read (Lua modules, data, priors, templates; the stdlib embedded in the binary), every program
// it ran, the libraries (--lib / SMI_PATH now, else the folder recorded), and the build of
// smi-lua. Each difference is listed (changed, with both hashes; missing; added files of a
// library). Exit status: 0 when everything matches, 1 on any difference, 2 when RESULTS is not
// a results file this smi-lua can read (not a regular file, too large, not JSON, no provenance,
// a newer schema) or the checks did not end within the time limit. A results file is data from
// whoever made it: only regular files are read (a recorded /dev/zero or FIFO is reported, never
// read), each up to the size it had when opened.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <variant>

#include "cli/commands.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/json.hpp"
#include "platform/core/path_walk.hpp"
#include "platform/core/printable.hpp"
#include "platform/core/run_record.hpp"
#include "platform/core/sha256.hpp"
#include "vm/build_info.hpp"
#include "vm/embedded_stdlib.hpp"

namespace smi::cli {
namespace fs = std::filesystem;
namespace {

/// RESULTS cannot be read as a results file: exit status 2 with this message.
struct NotResults : Error {
  using Error::Error;
};

/// One difference between what was recorded and what is at hand.
struct Diff {
  std::string what;      // "script", "file", "program", "library", "library file", "build"
  std::string name;      // path, library name, build component
  std::string change;    // "changed", "missing", "added", "removed"
  std::string recorded;  // digest or version as recorded ("" for added)
  std::string now;       // digest or version now ("" for missing/removed)
  std::string note;      // e.g. the file kind, the library's folder
};

struct RecordedLib {
  std::string name, version, path, hash, commit;
  std::map<std::string, std::string> files;
  bool has_files = false;
};

struct Recorded {
  int schema = 1;
  std::string smi_lua, script_path, script_hash, cwd;
  unsigned long long seed = 0;  // --seed takes any 64-bit unsigned value
  bool has_seed = false;
  std::vector<RecordedLib> libs;
  std::vector<std::pair<std::string, json::Value>> files;  // path -> {kind, hash, size, large, mtime}
  std::vector<json::Value> programs;
  std::vector<std::pair<std::string, std::string>> build;
  std::vector<std::string> command;
};

std::string field_string(const json::Value& o, const char* key) {
  const json::Value* v = o.find(key);
  return v && v->is_string() ? v->string() : "";
}

const char* const kExpected =
    "expected the results.json a study writes (smi.study; e.g. smi-out/<study>/results.json): a JSON object with "
    "\"schema\" and \"provenance\"";

/// A results file larger than this is not one a study wrote (its data are in other files).
constexpr std::size_t kMaxResultsBytes = std::size_t{256} << 20;

/// The results file's text: a regular file (a FIFO or a device would be read for ever), at most
/// kMaxResultsBytes.
std::string read_results_text(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) throw NotResults("cannot read '" + file.string() + "': " + std::strerror(errno));
  const pathwalk::Fd guard(fd);
  struct stat st;
  if (::fstat(fd, &st) != 0) throw NotResults("cannot read '" + file.string() + "': " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw NotResults("'" + file.string() + "' is not a regular file");
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxResultsBytes)
    throw NotResults("'" + file.string() + "' is " + std::to_string(st.st_size >> 20) +
                     " MB, more than a results file holds (at most " + std::to_string(kMaxResultsBytes >> 20) + " MB)");
  std::string text;
  if (!pathwalk::read_all(fd, text, kMaxResultsBytes))
    throw NotResults("cannot read '" + file.string() + "': " + std::strerror(errno));
  return text;
}

Recorded read_recorded(const fs::path& file) {
  const std::string text = read_results_text(file);
  json::Value doc;
  try {
    doc = json::read(text, file.string());
  } catch (const Error& e) {
    throw NotResults("'" + file.string() + "' is not valid JSON (" + e.what() + "); " + kExpected);
  }
  if (!doc.is_object()) throw NotResults("'" + file.string() + "' does not hold a JSON object; " + kExpected);
  Recorded r;
  if (const json::Value* s = doc.find("schema")) {
    const auto* i = std::get_if<std::int64_t>(&s->v);
    if (!i || *i < 1)
      throw NotResults("'" + file.string() + "': \"schema\" must be a whole number >= 1, got " + json::write(*s));
    if (*i > vm::kResultsSchema)
      throw NotResults("'" + file.string() + "' has schema " + std::to_string(*i) + ", newer than this smi-lua (" +
                       vm::host_version() + ") reads (schema " + std::to_string(vm::kResultsSchema) +
                       "): verify it with the smi-lua that wrote it (provenance.smi_lua) or a newer one");
    r.schema = static_cast<int>(*i);
  }
  const json::Value* prov = doc.find("provenance");
  if (!prov || !prov->is_object())
    throw NotResults("'" + file.string() + "' has no 'provenance' object; " + kExpected +
                     " (a hand-written results file can add provenance = smi.provenance())");
  r.smi_lua = field_string(*prov, "smi_lua");
  r.cwd = field_string(*prov, "cwd");
  if (const json::Value* seed = prov->find("seed"); seed && seed->is_number()) {
    // Read the integer itself: through a double, seeds above 2^53 came back as another seed.
    // The run stores smi.seed as a Lua integer (above 2^63: negative), hence the unsigned cast.
    if (const auto* i = std::get_if<std::int64_t>(&seed->v)) {
      r.seed = static_cast<unsigned long long>(*i);
      r.has_seed = true;
    } else if (const double d = seed->number(); d >= 0 && d < 18446744073709551616.0) {
      r.seed = static_cast<unsigned long long>(d);
      r.has_seed = true;
    }
  }
  if (const json::Value* script = prov->find("script"); script && script->is_object()) {
    r.script_path = field_string(*script, "path");
    r.script_hash = field_string(*script, "hash");
  }
  for (const json::Value& lib : prov->find("libraries") ? prov->find("libraries")->array() : json::Array{}) {
    if (!lib.is_object()) continue;
    RecordedLib l;
    l.name = field_string(lib, "name");
    l.version = field_string(lib, "version");
    l.path = field_string(lib, "path");
    l.hash = field_string(lib, "hash");
    l.commit = field_string(lib, "commit");
    if (const json::Value* files = lib.find("files"); files && files->is_object()) {
      l.has_files = true;
      for (const auto& [rel, digest] : files->object())
        if (digest.is_string()) l.files[rel] = digest.string();
    }
    r.libs.push_back(std::move(l));
  }
  if (const json::Value* files = prov->find("files"); files && files->is_object())
    for (const auto& [path, entry] : files->object()) r.files.emplace_back(path, entry);
  if (const json::Value* progs = prov->find("programs"); progs && progs->is_array()) r.programs = progs->array();
  if (const json::Value* build = prov->find("build"); build && build->is_object())
    for (const auto& [k, v] : build->object()) r.build.emplace_back(k, v.is_string() ? v.string() : json::write(v));
  if (const json::Value* cmd = prov->find("command"); cmd && cmd->is_array())
    for (const json::Value& w : cmd->array()) r.command.push_back(w.string());
  return r;
}

std::string commit_words(const std::string& c) { return c.empty() ? "no commit" : "commit " + c.substr(0, 12); }

/// A digest as text for messages: the hash, or "size N, mtime T (over 1 GB, not hashed)".
std::string digest_text(const FileDigest& d) {
  if (!d.large) return d.hash;
  return "size " + std::to_string(d.size) + ", mtime " + std::to_string(d.mtime) + " (over 1 GB, not hashed)";
}

FileDigest recorded_digest(const json::Value& e) {
  FileDigest d;
  d.hash = field_string(e, "hash");
  if (const json::Value* s = e.find("size")) d.size = static_cast<std::uintmax_t>(s->number());
  if (const json::Value* m = e.find("mtime")) d.mtime = static_cast<std::int64_t>(m->number());
  if (const json::Value* l = e.find("large")) d.large = std::holds_alternative<bool>(l->v) && std::get<bool>(l->v);
  return d;
}

bool same(const FileDigest& a, const FileDigest& b) {
  if (a.large || b.large) return a.large == b.large && a.size == b.size && a.mtime == b.mtime;
  return a.hash == b.hash;
}

/// The digest of a recorded path now: a file on disk, or "embedded:<path>" in this binary.
std::optional<FileDigest> digest_now(const std::string& path, std::string& why) {
  if (path.rfind("embedded:", 0) == 0) {
    const std::string rel = path.substr(std::strlen("embedded:"));
    for (const vm::EmbeddedModule* m = vm::kEmbeddedModules; m->name; ++m)
      if (rel == m->path) {
        FileDigest d;
        d.size = m->size;
        d.hash = "sha256:" + sha256_hex(std::string_view(m->data, m->size));
        return d;
      }
    why = "this smi-lua has no such embedded stdlib module";
    return std::nullopt;
  }
  try {
    return digest_path(path);
  } catch (const Error& e) {
    why = e.what();
    return std::nullopt;
  }
}

/// The recorded library against the one at hand (on the library path now, else at its recorded
/// folder). Prints its line in text mode; adds its differences.
void check_library(const RecordedLib& r, const vm::LibrarySet& here, bool text, std::vector<Diff>& diffs) {
  const vm::Library* cur = here.find(r.name);
  std::optional<vm::LibrarySet> at_recorded;
  std::string where = "on the library path";
  std::error_code ec;
  if (!cur && !r.path.empty() && fs::is_regular_file(fs::path(r.path) / vm::kManifestName, ec)) {
    at_recorded = vm::LibrarySet::discover({{r.path, "recorded path"}});
    cur = at_recorded->find(r.name);
    where = "at its recorded path";
  }
  if (!cur) {
    if (text)
      std::printf("MISSING  %s %s: not on the library path and not at %s; add its folder with --lib DIR\n",
                  r.name.c_str(), r.version.c_str(), r.path.empty() ? "(no recorded path)" : r.path.c_str());
    diffs.push_back({"library", r.name, "missing", r.hash, "", r.version + " at " + r.path});
    return;
  }
  const vm::FolderHash& h = cur->hash();
  const std::string& ver = cur->manifest.version.text;
  if (h.digest == r.hash) {
    if (text) {
      std::printf("ok       %s %s %s (%s), %s\n", r.name.c_str(), ver.c_str(), where.c_str(),
                  cur->folder.string().c_str(), h.digest.substr(0, 19).c_str());
      if (!r.commit.empty() && cur->git.commit != r.commit)
        std::printf("         same content, but the checkout is at %s (recorded %s)\n",
                    commit_words(cur->git.commit).c_str(), commit_words(r.commit).c_str());
    }
    return;
  }
  if (text) {
    std::printf("CHANGED  %s %s (%s): content differs from the recorded %s", r.name.c_str(), ver.c_str(),
                cur->folder.string().c_str(), r.version.c_str());
    if (ver != r.version) std::printf(" (version %s now)", ver.c_str());
    if (!r.commit.empty() || !cur->git.commit.empty())
      std::printf("; recorded %s, now %s", commit_words(r.commit).c_str(), commit_words(cur->git.commit).c_str());
    std::printf("\n         recorded %s\n         now      %s\n", r.hash.c_str(), h.digest.c_str());
  }
  diffs.push_back({"library", r.name, "changed", r.hash, h.digest, cur->folder.string()});
  if (!r.has_files) {
    if (text) std::printf("         (the results file has no per-file digests, so the changed files cannot be named)\n");
    return;
  }
  for (const auto& [rel, digest] : r.files) {
    const auto it = h.files.find(rel);
    if (it == h.files.end()) {
      if (text) std::printf("         removed: %s\n", rel.c_str());
      diffs.push_back({"library file", r.name + "/" + rel, "removed", digest, "", ""});
    } else if (it->second != digest) {
      if (text) std::printf("         changed: %s (recorded %s, now %s)\n", rel.c_str(), digest.substr(0, 16).c_str(),
                            it->second.substr(0, 16).c_str());
      diffs.push_back({"library file", r.name + "/" + rel, "changed", digest, it->second, ""});
    }
  }
  for (const auto& [rel, digest] : h.files)
    if (!r.files.count(rel)) {
      if (text) std::printf("         added:   %s\n", rel.c_str());
      diffs.push_back({"library file", r.name + "/" + rel, "added", "", digest, ""});
    }
}

/// A recorded file (or the script, or a program) against the one at hand.
void check_file(const std::string& what, const std::string& path, const std::string& kind, const FileDigest& rec,
                bool text, std::vector<Diff>& diffs) {
  std::string why;
  const std::optional<FileDigest> now = digest_now(path, why);
  const std::string label = what + (kind.empty() ? "" : " (" + kind + ")");
  if (!now) {
    if (text) std::printf("MISSING  %s %s: %s\n         recorded %s\n", label.c_str(), path.c_str(), why.c_str(),
                          digest_text(rec).c_str());
    diffs.push_back({what, path, "missing", digest_text(rec), "", why});
    return;
  }
  if (same(rec, *now)) return;
  if (text)
    std::printf("CHANGED  %s %s\n         recorded %s\n         now      %s\n", label.c_str(), path.c_str(),
                digest_text(rec).c_str(), digest_text(*now).c_str());
  diffs.push_back({what, path, "changed", digest_text(rec), digest_text(*now), kind});
}

bool inside_library(const std::string& path, const std::vector<RecordedLib>& libs) {
  for (const auto& l : libs)
    if (!l.path.empty() && pathwalk::within(path, l.path)) return true;
  return false;
}

/// A shell word: quoted when it holds anything but plain characters.
std::string shell_word(const std::string& w) {
  bool plain = !w.empty();
  for (char c : w)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_./=:,+@%", c))) plain = false;
  if (plain) return w;
  std::string q = "'";
  for (char c : w) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string command_text(const Recorded& rec) {
  if (rec.command.empty()) return "";
  std::string s = rec.cwd.empty() ? "" : "cd " + shell_word(rec.cwd) + " && ";
  for (std::size_t i = 0; i < rec.command.size(); ++i) s += (i ? " " : "") + shell_word(rec.command[i]);
  return s;
}

json::Value diffs_json(const std::string& file, const Recorded& rec, const std::vector<Diff>& diffs, int checked) {
  json::Array list;
  for (const Diff& d : diffs) {
    json::Object o{{"what", d.what}, {"name", d.name}, {"change", d.change}};
    if (!d.recorded.empty()) o.emplace_back("recorded", d.recorded);
    if (!d.now.empty()) o.emplace_back("now", d.now);
    if (!d.note.empty()) o.emplace_back("note", d.note);
    list.emplace_back(std::move(o));
  }
  json::Array cmd;
  for (const auto& w : rec.command) cmd.emplace_back(w);
  json::Object out{{"results", file},
                   {"schema", rec.schema},
                   {"reader_schema", vm::kResultsSchema},
                   {"match", diffs.empty()},
                   {"checked", checked},
                   {"differences", std::move(list)},
                   {"command", std::move(cmd)}};
  if (rec.has_seed) out.emplace_back("seed", static_cast<std::int64_t>(rec.seed));
  if (rec.schema < vm::kResultsSchema)
    out.emplace_back("note", "schema " + std::to_string(rec.schema) +
                                 " is older: files read, programs and the build were not recorded and are not checked");
  return out;
}

/// verify's time limit: --timeout, else kDefaultSeconds. A read that blocks (a network file
/// system, a file that never ends) cannot be interrupted from the reading thread, so a watcher
/// thread ends the process with exit status 2 ("could not verify"), naming what it was reading.
class TimeLimit {
 public:
  static constexpr double kDefaultSeconds = 600;

  explicit TimeLimit(double seconds) : seconds_(seconds > 0 ? seconds : kDefaultSeconds) {
    thread_ = std::thread([this] { watch(); });
  }
  ~TimeLimit() {
    {
      const std::lock_guard<std::mutex> lock(mu_);
      done_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  TimeLimit(const TimeLimit&) = delete;
  TimeLimit& operator=(const TimeLimit&) = delete;

  /// What is being checked now (named if the limit is reached).
  void at(std::string what) {
    const std::lock_guard<std::mutex> lock(mu_);
    now_ = std::move(what);
  }

 private:
  void watch() {
    std::unique_lock<std::mutex> lock(mu_);
    if (cv_.wait_for(lock, std::chrono::duration<double>(seconds_), [this] { return done_; })) return;
    const std::string msg = "smi-lua verify: the time limit of " + fmt::format("{:g}", seconds_) +
                            " s was reached while checking " + printable(now_) +
                            "; not every input was checked, so nothing is verified (give more time with "
                            "--timeout SECONDS)\n";
    (void)!::write(2, msg.data(), msg.size());
    ::_exit(2);
  }

  double seconds_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool done_ = false;
  std::string now_ = "the results file";
  std::thread thread_;
};

/// Every recorded input against the one at hand: libraries, the script, files, programs, the
/// build. Adds the differences; prints a line for each in text mode. Returns how many were checked.
int check_all(const Recorded& rec, const vm::LibrarySet& here, bool text, std::vector<Diff>& diffs, TimeLimit& limit) {
  int checked = 0;
  for (const RecordedLib& r : rec.libs) {
    ++checked;
    limit.at("library " + r.name);
    check_library(r, here, text, diffs);
  }
  if (!rec.script_path.empty()) {
    ++checked;
    limit.at("the script " + rec.script_path);
    FileDigest d;
    d.hash = rec.script_hash;
    check_file("script", rec.script_path, "", d, text, diffs);
  }
  for (const auto& [path, entry] : rec.files) {
    const std::string kind = field_string(entry, "kind");
    // The script and library files have their own checks above (one line each, not two).
    if (kind == "script" || kind == "program" || inside_library(path, rec.libs)) continue;
    ++checked;
    limit.at("'" + path + "'");
    check_file("file", path, kind, recorded_digest(entry), text, diffs);
  }
  for (const json::Value& p : rec.programs) {
    const std::string path = field_string(p, "path");
    if (path.empty()) continue;
    ++checked;
    limit.at("the program " + path);
    check_file("program", path, field_string(p, "name"), recorded_digest(p), text, diffs);
  }
  // The build: another compiler, Eigen or NLopt can move the last digits of a result.
  if (!rec.build.empty()) {
    for (const auto& [k, now] : vm::build_info()) {
      std::string was;
      for (const auto& [rk, rv] : rec.build)
        if (rk == k) was = rv;
      ++checked;
      if (was == now) continue;
      if (text)
        std::printf("CHANGED  build %s: recorded %s, this smi-lua %s\n", k.c_str(), was.empty() ? "(none)" : was.c_str(),
                    now.c_str());
      diffs.push_back({"build", k, "changed", was, now, ""});
    }
  } else if (text && !rec.smi_lua.empty() && rec.smi_lua != vm::host_version()) {
    std::printf("note     recorded with smi-lua %s, this is %s\n", rec.smi_lua.c_str(), vm::host_version());
  }

  return checked;
}

}  // namespace

int cmd_verify(const Args& a, const std::vector<std::string>& words) {
  bool as_json = false;
  std::vector<std::string> args;
  for (const auto& w : words) (w == "--json" ? as_json = true : (args.push_back(w), false));
  if (args.size() != 1) {
    std::fprintf(stderr,
                 "usage: smi-lua verify RESULTS.json [--json]   (the results file a study wrote, e.g. "
                 "smi-out/study/results.json)\n");
    return 2;
  }
  TimeLimit limit(a.cfg.timeout_s);
  limit.at("'" + args[0] + "'");
  Recorded rec;
  try {
    rec = read_recorded(args[0]);
  } catch (const NotResults& e) {
    std::fprintf(stderr, "smi-lua verify: %s\n", printable(e.what()).c_str());
    return 2;
  }
  // Everything shown comes from the results file: escaped, so a study cannot print its own
  // "ok" lines over the real ones with terminal escapes.
  for (std::string* f : {&rec.smi_lua, &rec.script_path, &rec.script_hash, &rec.cwd}) *f = printable(*f);
  for (std::string& c : rec.command) c = printable(c);
  for (auto& [path, info] : rec.files) path = printable(path);
  for (RecordedLib& l : rec.libs) {
    for (std::string* f : {&l.name, &l.version, &l.path, &l.hash, &l.commit}) *f = printable(*f);
    std::map<std::string, std::string> files;
    for (const auto& [rel, digest] : l.files) files[printable(rel)] = printable(digest);
    l.files = std::move(files);
  }
  const bool text = !as_json;
  limit.at("the library path");
  const vm::LibrarySet here = current_libraries(a);
  std::vector<Diff> diffs;
  if (text) {
    std::printf("verifying %s (schema %d): %zu librar%s, %zu file%s, %zu program%s recorded", args[0].c_str(), rec.schema,
                rec.libs.size(), rec.libs.size() == 1 ? "y" : "ies", rec.files.size(), rec.files.size() == 1 ? "" : "s",
                rec.programs.size(), rec.programs.size() == 1 ? "" : "s");
    if (!rec.smi_lua.empty()) std::printf(", smi-lua %s", rec.smi_lua.c_str());
    if (rec.has_seed) std::printf(", seed %llu", rec.seed);
    std::printf("\n");
    if (rec.schema < vm::kResultsSchema)
      std::printf("note     schema %d is older than this smi-lua's (%d): it recorded only the script, the seed and the "
                  "libraries, so files read, programs and the build are not checked\n",
                  rec.schema, vm::kResultsSchema);
  }

  const int checked = check_all(rec, here, text, diffs, limit);

  if (as_json) {
    std::printf("%s\n", json::write(diffs_json(args[0], rec, diffs, checked), {.indent = 2}).c_str());
    return diffs.empty() ? 0 : 1;
  }
  const std::string cmd = command_text(rec);
  if (diffs.empty()) {
    if (rec.has_seed)
      std::printf("verify: everything matches; rerun with --seed %llu to reproduce the results (%d checked)\n",
                  rec.seed, checked);
    else
      std::printf("verify: everything matches (%d checked)\n", checked);
    if (!cmd.empty()) std::printf("the run was: %s\n", cmd.c_str());
    return 0;
  }
  int libs_changed = 0, missing = 0;
  for (const Diff& d : diffs) {
    libs_changed += d.what == "library" && d.change == "changed";
    missing += d.change == "missing";
  }
  std::printf("verify: %zu difference%s (%d librar%s changed, %d missing): the inputs at hand are not the ones that "
              "produced the results\n",
              diffs.size(), diffs.size() == 1 ? "" : "s", libs_changed, libs_changed == 1 ? "y" : "ies", missing);
  return 1;
}

}  // namespace smi::cli
