// SPDX-License-Identifier: MIT
#include "vm/project_manifest.hpp"

#include <fstream>
#include <sstream>

#include "platform/core/atomic_file.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/json.hpp"
#include "vm/manifest.hpp"

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

std::string text_field(const json::Value& o, const char* key, const std::string& where) {
  const json::Value* v = o.find(key);
  if (!v) return "";
  if (!v->is_string()) throw Error(where + ": field '" + key + "' must be a string");
  return v->string();
}

}  // namespace

Requirement DirectRequirement::requirement() const { return Requirement::parse(range.empty() ? name : name + " " + range); }

ProjectManifest read_project_manifest(const fs::path& file) {
  ProjectManifest m;
  std::ifstream in(file, std::ios::binary);
  if (!in) return m;
  m.exists = true;
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string where = "project manifest '" + file.string() + "'";
  const std::string fix = " (smi-lua libs add writes it; see docs/sharing-libraries.md for its form)";
  json::Value doc;
  try {
    doc = json::read(ss.str(), file.string());
  } catch (const Error& e) {
    throw Error(where + " is not valid JSON: " + e.what() + fix);
  }
  if (!doc.is_object()) throw Error(where + " does not hold a JSON object" + fix);
  const json::Value* ver = doc.find("project");
  if (!ver || !ver->is_number() || ver->number() != 1)
    throw Error(where + ": field 'project' must be 1 (this smi-lua reads project manifest format 1)" + fix);
  if (const json::Value* regs = doc.find("registries")) {
    if (!regs->is_object()) throw Error(where + ": field 'registries' must map names to git URLs" + fix);
    for (const auto& [name, url] : regs->object()) {
      if (!valid_library_name(name))
        throw Error(where + ": registry name '" + name + "' must be letters, digits and '_' (not starting with a digit)");
      if (!url.is_string() || url.string().empty())
        throw Error(where + ": registry '" + name + "' must be a git URL (file://, https:// or ssh://)");
      m.registries[name] = url.string();
    }
  }
  if (const json::Value* reqs = doc.find("requires")) {
    if (!reqs->is_object()) throw Error(where + ": field 'requires' must map library names to {version, source}" + fix);
    for (const auto& [name, v] : reqs->object()) {
      const std::string at = where + ", requirement '" + name + "'";
      if (!valid_library_name(name)) throw Error(at + ": not a valid library name" + fix);
      if (!v.is_object()) throw Error(at + ": must be an object like {\"version\": \"^1.2.0\", \"source\": \"URL\"}");
      DirectRequirement r;
      r.name = name;
      r.range = text_field(v, "version", at);
      r.source = text_field(v, "source", at);
      r.registry = text_field(v, "registry", at);
      try {
        (void)r.requirement();
      } catch (const Error& e) {
        throw Error(at + ": field 'version': " + e.what());
      }
      if (!r.registry.empty() && !m.registries.count(r.registry))
        throw Error(at + ": registry '" + r.registry + "' is not in 'registries'; add it with smi-lua libs registry " +
                    r.registry + " URL");
      m.requires_[name] = std::move(r);
    }
  }
  return m;
}

void write_project_manifest(const ProjectManifest& m, const fs::path& file) {
  json::Object regs, reqs;
  for (const auto& [name, url] : m.registries) regs.emplace_back(name, url);
  for (const auto& [name, r] : m.requires_) {
    json::Object o{{"version", r.range}};
    if (!r.source.empty()) o.emplace_back("source", r.source);
    if (!r.registry.empty()) o.emplace_back("registry", r.registry);
    reqs.emplace_back(name, std::move(o));
  }
  const json::Value doc(json::Object{{"project", 1}, {"registries", std::move(regs)}, {"requires", std::move(reqs)}});
  json::WriteOptions o;
  o.indent = 2;
  write_file_atomic(file.string(), json::write(doc, o) + "\n");
}

}  // namespace smi::vm
