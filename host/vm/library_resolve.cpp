// SPDX-License-Identifier: MIT
#include "vm/library_resolve.hpp"

#include <algorithm>

#include "platform/core/errors.hpp"

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

std::string versions_seen(const std::vector<Candidate>& cands) {
  std::string s;
  for (const auto& c : cands) s += (s.empty() ? "" : ", ") + (c.ref.empty() ? c.version.text : c.ref);
  return s.empty() ? "none (no tag names a version, like v1.2.0)" : s;
}

}  // namespace

const std::vector<Candidate>& VersionFinder::at_source(const std::string& source) {
  const auto it = tags_.find(source);
  if (it != tags_.end()) return it->second;
  std::vector<Candidate> out;
  for (const VersionTag& t : version_tags(source, place_)) out.push_back({t.version, source, t.tag, "", "", ""});
  return tags_[source] = std::move(out);
}

const Registry& VersionFinder::registry(const std::string& name, const std::string& url) {
  const auto it = clones_.find(name);
  if (it != clones_.end()) return it->second;
  return clones_.emplace(name, Registry::clone(url, place_, "registry-" + name)).first->second;
}

std::vector<Candidate> VersionFinder::in_registries(const std::string& name, const std::string& only) {
  std::vector<Candidate> out;
  for (const auto& [rname, url] : registries_) {
    if (!only.empty() && rname != only) continue;
    for (const RegistryEntry& e : registry(rname, url).versions(name)) {
      const Version v = Version::parse(e.version);
      bool dup = false;
      for (const Candidate& c : out) dup = dup || compare(c.version, v) == 0;
      if (!dup) out.push_back({v, e.source, e.ref.empty() ? e.commit : e.ref, e.commit, e.checksum, url});
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return compare(a.version, b.version) > 0; });
  return out;
}

std::string VersionFinder::registries_text() const {
  std::string s;
  for (const auto& [name, url] : registries_) s += (s.empty() ? "" : ", ") + name + " (" + url + ")";
  return s.empty() ? "none" : s;
}

Fetched VersionFinder::fetch(const Candidate& c, const std::string& name, const fs::path& dest) {
  const Fetched f = fetch_library(c.source, c.ref, dest, place_);
  const std::string what = name + " " + c.version.text + " from " + c.source + (c.ref.empty() ? "" : " at " + c.ref);
  if (f.manifest.name != name)
    throw Error(what + " holds library '" + f.manifest.name + "', not '" + name + "'" +
                (c.registry.empty() ? "" : "; the registry " + c.registry + " records it wrongly: tell its publisher"));
  if (compare(f.manifest.version, c.version) != 0)
    throw Error(what + " holds version " + f.manifest.version.text + " in its smi-lib.lua, not " + c.version.text);
  if (!c.registry.empty()) {
    if (!c.commit.empty() && f.commit != c.commit)
      throw Error(what + " is commit " + f.commit + ", but the registry " + c.registry + " recorded commit " + c.commit +
                  " when it was published (the tag was moved); nothing was installed: ask the publisher to restore "
                  "the tag, or publish a new version");
    if (f.hash.digest != c.checksum)
      throw Error(what + ": its files hash to " + f.hash.digest + ", but the registry " + c.registry + " recorded " +
                  c.checksum + " when it was published; nothing was installed: the source changed after publishing");
  }
  return f;
}

LockEntry entry_of(const Fetched& f, const std::string& source) {
  LockEntry e;
  e.name = f.manifest.name;
  e.version = f.manifest.version.text;
  e.source = source;
  e.ref = f.ref;
  e.commit = f.commit;
  for (const auto& r : f.manifest.requires_) e.requires_.push_back(r.text);
  e.hash = f.hash.digest;
  e.files = f.hash.files;
  return e;
}

const Candidate* best_candidate(const std::vector<Candidate>& cands, const std::vector<const Requirement*>& on) {
  for (const Candidate& c : cands) {
    bool ok = true;
    for (const Requirement* r : on) ok = ok && r->accepts(c.version);
    if (ok) return &c;
  }
  return nullptr;
}

void resolve(std::map<std::string, Planned>& plan, VersionFinder& finder, int& counter) {
  for (int round = 0; round < 100; ++round) {
    bool changed = false;
    for (const auto& [who, item] : plan) {
      for (const Requirement& r : item.requires_) {
        if (r.name == "smi-lua") continue;
        // every requirement on r.name, from every library planned
        std::vector<std::pair<const Planned*, const Requirement*>> on;
        std::vector<const Requirement*> reqs;
        for (const auto& [n, p] : plan)
          for (const auto& q : p.requires_)
            if (q.name == r.name) {
              on.emplace_back(&p, &q);
              reqs.push_back(&q);
            }
        const auto requirers = [&] {
          std::string s;
          for (const auto& [p, q] : on)
            s += (s.empty() ? "" : "; ") + p->entry.name + " " + p->entry.version + " requires '" + q->text + "'";
          return s;
        };
        const auto have = plan.find(r.name);
        if (have != plan.end()) {
          const Version hv = Version::parse(have->second.entry.version);
          bool all = true;
          for (const Requirement* q : reqs) all = all && q->accepts(hv);
          if (all) continue;
          if (have->second.pinned)
            throw Error("you asked for " + r.name + " " + have->second.entry.version + ", but " + requirers() +
                        "; add a version of " + r.name + " that satisfies it, or first a release of the requiring "
                        "library that accepts " + have->second.entry.version);
        }
        std::string source;
        if (const auto s = item.sources.find(r.name); s != item.sources.end()) source = s->second;
        else if (have != plan.end()) source = have->second.entry.source;
        const std::string asker = who + " " + item.entry.version + " requires '" + r.text + "'";
        std::vector<Candidate> cands;
        std::string where;
        if (!source.empty()) {
          cands = finder.at_source(source);
          where = source;
        } else if (finder.has_registries()) {
          cands = finder.in_registries(r.name);
          where = "the registries " + finder.registries_text();
        } else {
          throw Error(asker + ", but its " + std::string(kManifestName) + " names no source for " + r.name +
                      " (sources = {" + r.name + " = \"URL\"}), smi-lock.json holds none and smi-project.json names "
                      "no registry; add it first: smi-lua libs add URL@TAG (or its .tar.gz), then add this again");
        }
        const Candidate* pick = best_candidate(cands, reqs);
        if (!pick)
          throw Error("no version of " + r.name + " at " + where + " satisfies every requirement on it (" + requirers() +
                      "); versions seen: " + versions_seen(cands) +
                      ". Ask for a release that does, or add releases of the requiring libraries that agree");
        const fs::path dir = finder.place().scratch / ("lib" + std::to_string(++counter));
        Fetched f;
        try {
          f = finder.fetch(*pick, r.name, dir);
        } catch (const Error& e) {
          throw Error(asker + ": " + e.what() + "; if its source cannot be reached from here, add " + r.name +
                      " first from where you can (smi-lua libs add its .tar.gz or another URL), then add this again");
        }
        Planned p;
        p.entry = entry_of(f, pick->source);
        p.requires_ = f.manifest.requires_;
        p.sources = f.manifest.sources;
        p.staged = dir;
        p.why = "required by " + who;
        plan[r.name] = std::move(p);
        changed = true;
        break;
      }
      if (changed) break;
    }
    if (!changed) return;
  }
  throw Error("the requirements do not settle after 100 rounds (libraries requiring each other's older versions); "
              "add the libraries one by one at versions that agree");
}

}  // namespace smi::vm
