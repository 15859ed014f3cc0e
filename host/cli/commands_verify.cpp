// smi-lua verify RESULTS.json: compares the provenance a study recorded (smi.provenance() in
// its results file) with the libraries at hand: the ones --lib / SMI_PATH give now, or, for a
// library not found there, the folder it was recorded at. Names every changed, added or removed
// file. Exit status 0 when everything matches, 1 otherwise.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <variant>

#include "cli/commands.hpp"
#include "kernels/core/errors.hpp"
#include "kernels/core/json.hpp"
#include "kernels/core/printable.hpp"
#include "kernels/core/sha256.hpp"

namespace smi::cli {
namespace fs = std::filesystem;
namespace {

struct RecordedLib {
  std::string name, version, path, hash, commit;
  std::map<std::string, std::string> files;
  bool has_files = false;
};

struct Recorded {
  std::string smi_lua, script_path, script_hash;
  unsigned long long seed = 0;  // --seed takes any 64-bit unsigned value
  bool has_seed = false;
  std::vector<RecordedLib> libs;
};

std::string field_string(const json::Value& o, const char* key) {
  const json::Value* v = o.find(key);
  return v ? v->string() : "";
}

Recorded read_recorded(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("cannot read '" + file.string() + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  json::Value doc;
  try {
    doc = json::read(ss.str(), file.string());
  } catch (const Error& e) {
    throw Error("'" + file.string() + "' is not valid JSON: " + e.what());
  }
  if (!doc.is_object()) throw Error("'" + file.string() + "' does not hold a JSON object");
  const json::Value* prov = doc.find("provenance");
  if (!prov || !prov->is_object())
    throw Error("'" + file.string() +
                "' has no 'provenance' object: it was not written by a study that records smi.provenance() "
                "(smi.study does; a hand-written results file can add provenance = smi.provenance())");
  Recorded r;
  r.smi_lua = field_string(*prov, "smi_lua");
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
  if (const json::Value* libs = prov->find("libraries")) {
    for (const json::Value& lib : libs->array()) {
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
  }
  return r;
}

std::string short_commit(const std::string& c) { return c.empty() ? "no commit" : "commit " + c.substr(0, 12); }

enum class LibraryCheck { ok, changed, missing };

// One recorded library against the one at hand (on the library path now, else at its recorded
// folder): a line saying ok, CHANGED (with the files that differ, when recorded) or MISSING.
LibraryCheck check_library(const RecordedLib& r, const vm::LibrarySet& here) {
  // The library at hand: the one on the library path now, else the recorded folder.
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
    std::printf("MISSING  %s %s: not on the library path and not at %s; add its folder with --lib DIR\n",
                r.name.c_str(), r.version.c_str(), r.path.empty() ? "(no recorded path)" : r.path.c_str());
    return LibraryCheck::missing;
  }
  const vm::FolderHash& h = cur->hash();
  const std::string& ver = cur->manifest.version.text;
  if (h.digest == r.hash) {
    std::printf("ok       %s %s %s (%s), %s\n", r.name.c_str(), ver.c_str(), where.c_str(), cur->folder.string().c_str(),
                h.digest.substr(0, 19).c_str());
    if (!r.commit.empty() && cur->git.commit != r.commit)
      std::printf("         same content, but the checkout is at %s (recorded %s)\n", short_commit(cur->git.commit).c_str(),
                  short_commit(r.commit).c_str());
    return LibraryCheck::ok;
  }
  std::printf("CHANGED  %s %s (%s): content differs from the recorded %s", r.name.c_str(), ver.c_str(),
              cur->folder.string().c_str(), r.version.c_str());
  if (ver != r.version) std::printf(" (version %s now)", ver.c_str());
  if (!r.commit.empty() || !cur->git.commit.empty())
    std::printf("; recorded %s, now %s", short_commit(r.commit).c_str(), short_commit(cur->git.commit).c_str());
  std::printf("\n");
  if (!r.has_files) {
    std::printf("         (the results file has no per-file digests, so the changed files cannot be named)\n");
    return LibraryCheck::changed;
  }
  for (const auto& [rel, digest] : r.files) {
    const auto it = h.files.find(rel);
    if (it == h.files.end()) std::printf("         removed: %s\n", rel.c_str());
    else if (it->second != digest) std::printf("         changed: %s\n", rel.c_str());
  }
  for (const auto& [rel, digest] : h.files)
    if (!r.files.count(rel)) std::printf("         added:   %s\n", rel.c_str());
  return LibraryCheck::changed;
}

}  // namespace

int cmd_verify(const Args& a, const std::vector<std::string>& args) {
  if (args.size() != 1) {
    std::fprintf(stderr, "usage: smi-lua verify RESULTS.json   (the results file a study wrote, e.g. smi-out/study/results.json)\n");
    return 2;
  }
  // Everything shown comes from the results file: escaped, so a study cannot print its own
  // "ok" lines over the real ones with terminal escapes.
  Recorded rec = read_recorded(args[0]);
  for (std::string* f : {&rec.smi_lua, &rec.script_path, &rec.script_hash}) *f = printable(*f);
  for (RecordedLib& l : rec.libs) {
    for (std::string* f : {&l.name, &l.version, &l.path, &l.hash, &l.commit}) *f = printable(*f);
    std::map<std::string, std::string> files;
    for (const auto& [rel, digest] : l.files) files[printable(rel)] = printable(digest);
    l.files = std::move(files);
  }
  const vm::LibrarySet here = current_libraries(a);
  int changed = 0, missing = 0;
  std::printf("verifying %s: %zu librar%s recorded", args[0].c_str(), rec.libs.size(), rec.libs.size() == 1 ? "y" : "ies");
  if (!rec.smi_lua.empty()) std::printf(", smi-lua %s", rec.smi_lua.c_str());
  if (rec.has_seed) std::printf(", seed %llu", rec.seed);
  std::printf("\n");

  for (const RecordedLib& r : rec.libs) {
    const LibraryCheck c = check_library(r, here);
    changed += c == LibraryCheck::changed;
    missing += c == LibraryCheck::missing;
  }

  bool script_changed = false;
  if (!rec.script_path.empty()) {
    std::error_code ec;
    if (!fs::is_regular_file(rec.script_path, ec)) {
      std::printf("note     study script %s is not here (not checked)\n", rec.script_path.c_str());
    } else if ("sha256:" + sha256_file(rec.script_path) != rec.script_hash) {
      script_changed = true;
      std::printf("CHANGED  study script %s differs from the one that produced the results\n", rec.script_path.c_str());
    } else {
      std::printf("ok       study script %s\n", rec.script_path.c_str());
    }
  }
  if (!rec.smi_lua.empty() && rec.smi_lua != vm::host_version())
    std::printf("note     recorded with smi-lua %s, this is %s\n", rec.smi_lua.c_str(), vm::host_version());

  const bool all_ok = changed == 0 && missing == 0 && !script_changed;
  if (all_ok && rec.has_seed)
    std::printf("verify: everything matches; rerun with --seed %llu to reproduce the results\n", rec.seed);
  else if (all_ok)
    std::printf("verify: everything matches\n");
  else
    std::printf("verify: %d librar%s changed, %d missing%s: the code at hand is not the code that produced the results\n",
                changed, changed == 1 ? "y" : "ies", missing, script_changed ? ", study script changed" : "");
  return all_ok ? 0 : 1;
}

}  // namespace smi::cli
