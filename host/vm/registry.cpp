// SPDX-License-Identifier: MIT
#include "vm/registry.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "platform/core/errors.hpp"
#include "platform/core/json.hpp"
#include "vm/manifest.hpp"

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kIndexFileMax = 16u << 20;  // one library's index file

std::string field(const json::Value& o, const char* key, const std::string& where, bool required) {
  const json::Value* v = o.find(key);
  if (!v && !required) return "";
  if (!v || !v->is_string()) throw Error(where + ": field '" + key + "' is missing or not a string");
  return v->string();
}

RegistryEntry parse_line(const std::string& line, const std::string& name, const std::string& where) {
  json::Value v;
  try {
    v = json::read(line, where);
  } catch (const Error& e) {
    throw Error(where + " is not a JSON line: " + e.what());
  }
  if (!v.is_object()) throw Error(where + " is not a JSON object");
  RegistryEntry e;
  e.name = field(v, "name", where, true);
  if (e.name != name) throw Error(where + " names library '" + e.name + "', not '" + name + "'");
  e.version = field(v, "version", where, true);
  (void)Version::parse(e.version);  // the version grammar, as everywhere a version enters
  e.source = field(v, "source", where, true);
  e.ref = field(v, "ref", where, false);
  e.commit = field(v, "commit", where, false);
  e.checksum = field(v, "checksum", where, true);
  e.description = field(v, "description", where, false);
  if (const json::Value* r = v.find("requires"))
    for (const json::Value& x : r->array()) {
      if (!x.is_string()) throw Error(where + ": field 'requires' must hold strings");
      (void)Requirement::parse(x.string());
      e.requires_.push_back(x.string());
    }
  return e;
}

std::string read_small(const fs::path& p) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(p, ec))) return "";
  if (fs::file_size(p, ec) > kIndexFileMax) throw Error("registry index file '" + p.string() + "' is too large");
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

fs::path registry_index_file(const std::string& name) {
  if (!valid_library_name(name)) throw Error("'" + name + "' is not a library name, so it has no registry index file");
  return fs::path("index") / name;
}

Registry Registry::clone(const std::string& url, const GitPlace& place, const std::string& folder) {
  check_git_address(url);
  Registry r;
  r.url_ = url;
  r.dir_ = place.scratch / folder;
  r.place_ = place;
  fs::remove_all(r.dir_);
  const GitResult g = run_git({"clone", "--quiet", "--template=", "--", url, r.dir_.string()}, place);
  if (g.status != 0)
    throw Error("cannot reach the registry '" + url + "': git clone failed: " + git_reason(g.err) +
                "; a registry is a git repository (make one with: git init --bare DIR)");
  return r;
}

std::vector<RegistryEntry> Registry::versions(const std::string& name) const {
  const fs::path rel = registry_index_file(name);
  std::vector<RegistryEntry> out;
  std::stringstream ss(read_small(dir_ / rel));
  int n = 0;
  for (std::string line; std::getline(ss, line);) {
    ++n;
    if (line.empty()) continue;
    out.push_back(parse_line(line, name, "registry " + url_ + ", " + rel.generic_string() + " line " + std::to_string(n)));
  }
  std::stable_sort(out.begin(), out.end(), [](const RegistryEntry& a, const RegistryEntry& b) {
    return compare(Version::parse(a.version), Version::parse(b.version)) > 0;
  });
  return out;
}

std::vector<std::string> Registry::names() const {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir_ / "index", ec)) {
    const std::string n = e.path().filename().string();
    if (valid_library_name(n) && fs::is_regular_file(e.symlink_status(ec))) out.push_back(n);
  }
  std::sort(out.begin(), out.end());
  return out;
}

void Registry::publish(const RegistryEntry& e) const {
  for (const RegistryEntry& old : versions(e.name))
    if (compare(Version::parse(old.version), Version::parse(e.version)) == 0)
      throw Error(e.name + " " + old.version + " is published already in " + url_ + " (from " + old.source +
                  (old.commit.empty() ? "" : " at " + old.commit.substr(0, 12)) +
                  "); a published version is never replaced: publish a new version (" + e.name + " " + e.version +
                  " -> raise the version in smi-lib.lua and tag it)");
  json::Array reqs;
  for (const auto& r : e.requires_) reqs.emplace_back(r);
  const json::Value line(json::Object{{"name", e.name},         {"version", e.version}, {"source", e.source},
                                      {"ref", e.ref},           {"commit", e.commit},   {"checksum", e.checksum},
                                      {"requires", std::move(reqs)}, {"description", e.description}});
  const fs::path rel = registry_index_file(e.name);
  fs::create_directories(dir_ / "index");
  {
    std::ofstream out(dir_ / rel, std::ios::binary | std::ios::app);
    out << json::write(line) << "\n";
    out.close();
    if (!out) throw Error("cannot write '" + (dir_ / rel).string() + "'");
  }
  const std::string d = dir_.string();
  const char* user = std::getenv("USER");
  const std::string who = user && *user ? user : "smi-lua";
  const auto git = [&](std::vector<std::string> args, const std::string& what) {
    args.insert(args.begin(), {"-C", d, "-c", "user.name=" + who, "-c", "user.email=" + who + "@smi-lua.invalid"});
    const GitResult g = run_git(args, place_);
    if (g.status != 0) throw Error("cannot publish to the registry '" + url_ + "': git " + what + " failed: " + git_reason(g.err));
    return g;
  };
  git({"add", "--", rel.generic_string()}, "add");
  git({"commit", "--quiet", "--no-verify", "-m", "publish " + e.name + " " + e.version}, "commit");
  const GitResult head = git({"symbolic-ref", "--quiet", "HEAD"}, "symbolic-ref");
  std::string branch = head.out;
  while (!branch.empty() && (branch.back() == '\n' || branch.back() == '\r')) branch.pop_back();
  const GitResult p = run_git({"-C", d, "push", "--quiet", "--no-verify", "origin", "HEAD:" + branch}, place_);
  if (p.status != 0)
    throw Error("the registry '" + url_ + "' refused the publication of " + e.name + " " + e.version + ": " +
                git_reason(p.err) + " (someone may have published at the same time: run the command again)");
}

}  // namespace smi::vm
