// SPDX-License-Identifier: MIT
#include "vm/lockfile.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "platform/core/atomic_file.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/json.hpp"
#include "platform/core/sha256.hpp"
#include "vm/folder_hash.hpp"
#include "vm/manifest.hpp"
#include "vm/semver.hpp"

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

std::string entry_checksum(const LockEntry& e) {
  Sha256 h;
  h.field("smi-lock-entry-v1").field(e.name).field(e.version).field(e.source).field(e.ref).field(e.commit);
  h.field(std::to_string(e.requires_.size()));
  for (const auto& r : e.requires_) h.field(r);
  h.field(e.hash).field(std::to_string(e.files.size()));
  for (const auto& [path, digest] : e.files) h.field(path).field(digest);
  return "sha256:" + h.hex();
}

std::string file_checksum(const Lockfile& l) {
  Sha256 h;
  h.field("smi-lock-v1").field(l.tree);
  for (const LockEntry& e : l.libs) h.field(entry_checksum(e));
  return "sha256:" + h.hex();
}

std::string fix_hint() {
  return "smi-lock.json is written by `smi-lua libs add` and `libs remove`: restore the committed file (git checkout "
         "smi-lock.json) or add the library again";
}

std::string str(const json::Value& o, const char* key, const std::string& where, bool required = true) {
  const json::Value* v = o.find(key);
  if (!v || !v->is_string()) {
    if (!required && !v) return "";
    throw Error(where + ": field '" + key + "' is missing or not a string; " + fix_hint());
  }
  return v->string();
}

}  // namespace

const LockEntry* Lockfile::find(const std::string& name) const {
  for (const LockEntry& e : libs)
    if (e.name == name) return &e;
  return nullptr;
}

void Lockfile::put(LockEntry e) {
  erase(e.name);
  libs.push_back(std::move(e));
  std::sort(libs.begin(), libs.end(), [](const LockEntry& a, const LockEntry& b) { return a.name < b.name; });
}

bool Lockfile::erase(const std::string& name) {
  const auto it = std::find_if(libs.begin(), libs.end(), [&](const LockEntry& e) { return e.name == name; });
  if (it == libs.end()) return false;
  libs.erase(it);
  return true;
}

fs::path lock_tree(const Lockfile& lock, const fs::path& lockfile) {
  const fs::path t(lock.tree);
  return t.is_absolute() ? t : lockfile.parent_path() / t;
}

bool tree_inside_project(const std::string& tree) {
  if (tree.empty() || tree.find('\0') != std::string::npos) return false;
  const fs::path t(tree);
  if (t.is_absolute()) return false;
  for (const auto& part : t.lexically_normal())
    if (part == "..") return false;
  return t.lexically_normal() != ".";
}

std::vector<std::string> lock_differences(const std::map<std::string, std::string>& want,
                                          const std::map<std::string, std::string>& have) {
  std::vector<std::string> out;
  for (const auto& [path, digest] : want) {
    const auto it = have.find(path);
    if (it == have.end()) out.push_back("file '" + path + "' is missing");
    else if (it->second != digest) out.push_back("file '" + path + "' differs from smi-lock.json (SHA-256 " +
                                                 it->second.substr(0, 12) + ", locked " + digest.substr(0, 12) + ")");
  }
  for (const auto& [path, digest] : have)
    if (!want.count(path)) out.push_back("file '" + path + "' is not in smi-lock.json");
  return out;
}

Lockfile read_lockfile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("cannot read the lockfile '" + file.string() + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  json::Value doc;
  try {
    doc = json::read(ss.str(), file.string());
  } catch (const Error& e) {
    throw Error("the lockfile '" + file.string() + "' is not valid JSON: " + e.what() + "; " + fix_hint());
  }
  const std::string where = "lockfile '" + file.string() + "'";
  if (!doc.is_object()) throw Error(where + " does not hold a JSON object; " + fix_hint());
  const json::Value* ver = doc.find("lockfile");
  if (!ver || !ver->is_number() || ver->number() != 1)
    throw Error(where + ": field 'lockfile' must be 1 (this smi-lua reads lockfile format 1); " + fix_hint());
  Lockfile lock;
  lock.tree = str(doc, "tree", where);
  const json::Value* libs = doc.find("libraries");
  if (!libs || !libs->is_array()) throw Error(where + ": field 'libraries' is missing or not a list; " + fix_hint());
  for (const json::Value& v : libs->array()) {
    if (!v.is_object()) throw Error(where + ": an entry of 'libraries' is not an object; " + fix_hint());
    LockEntry e;
    e.name = str(v, "name", where);
    const std::string at = where + ", library '" + e.name + "'";
    if (!valid_library_name(e.name)) throw Error(at + ": not a valid library name; " + fix_hint());
    e.version = str(v, "version", at);
    try {
      Version::parse(e.version);
    } catch (const Error& err) {
      throw Error(at + ": field 'version': " + err.what() + "; " + fix_hint());
    }
    e.source = str(v, "source", at);
    e.ref = str(v, "ref", at, false);
    e.commit = str(v, "commit", at, false);
    e.hash = str(v, "hash", at);
    if (const json::Value* r = v.find("requires"))
      for (const json::Value& x : r->array()) e.requires_.push_back(x.string());
    const json::Value* files = v.find("files");
    if (!files || !files->is_object()) throw Error(at + ": field 'files' is missing or not an object; " + fix_hint());
    for (const auto& [path, digest] : files->object()) {
      if (!digest.is_string() || digest.string().size() != 64)
        throw Error(at + ": the SHA-256 of file '" + path + "' is not 64 hex digits; " + fix_hint());
      e.files[path] = digest.string();
    }
    const std::string sum = str(v, "checksum", at, false);
    if (sum != entry_checksum(e) || e.hash != combine_file_hashes(e.files))
      throw Error(at + " " + e.version + " was edited by hand: its checksum does not match its fields; " + fix_hint());
    if (lock.find(e.name)) throw Error(at + " appears twice (a study sees one version of each library); " + fix_hint());
    lock.libs.push_back(std::move(e));
  }
  std::sort(lock.libs.begin(), lock.libs.end(), [](const LockEntry& a, const LockEntry& b) { return a.name < b.name; });
  if (str(doc, "checksum", where, false) != file_checksum(lock))
    throw Error(where + " was edited by hand: a library entry was added or removed, or the tree changed, without "
                "`smi-lua libs add`/`libs remove`; " + fix_hint());
  return lock;
}

void write_lockfile(const Lockfile& lock, const fs::path& file) {
  json::Array libs;
  for (const LockEntry& e : lock.libs) {
    json::Array req;
    for (const auto& r : e.requires_) req.emplace_back(r);
    json::Object files;
    for (const auto& [path, digest] : e.files) files.emplace_back(path, digest);
    libs.emplace_back(json::Object{{"name", e.name},        {"version", e.version},  {"source", e.source},
                                   {"ref", e.ref},          {"commit", e.commit},    {"requires", std::move(req)},
                                   {"hash", e.hash},        {"files", std::move(files)},
                                   {"checksum", entry_checksum(e)}});
  }
  const json::Value doc(json::Object{{"lockfile", 1},
                                     {"tree", lock.tree},
                                     {"libraries", std::move(libs)},
                                     {"checksum", file_checksum(lock)}});
  json::WriteOptions o;
  o.indent = 2;
  const std::string text = json::write(doc, o) + "\n";
  write_file_atomic(file.string(), text);
}

}  // namespace smi::vm
