// smi-lua libs add / sync / remove / outdated: the project's library tree (./smi-libs/<name>/
// <version>/, or --into DIR) and its smi-lock.json, in the current folder.
//
// Everything is fetched into a temporary folder inside the tree first (vm/library_sources.hpp:
// no library code runs), checked (manifest against the tag, requirements, hashes against the
// lockfile), and only then renamed into place, so a failure leaves nothing half-installed.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

#include "cli/commands.hpp"
#include "platform/core/errors.hpp"
#include "vm/library_sources.hpp"
#include "vm/lockfile.hpp"

namespace smi::cli {
namespace fs = std::filesystem;
namespace {

/// A temporary folder inside the tree (same file system, so installing is a rename), removed
/// when done whatever happened.
struct Scratch {
  fs::path dir, made_tree;  // made_tree: the tree, when this created it (removed again if left empty)
  explicit Scratch(const fs::path& tree) {
    std::error_code ec;
    if (!fs::exists(tree, ec)) made_tree = tree;
    fs::create_directories(tree, ec);
    if (ec) throw Error("cannot create the library tree '" + tree.string() + "': " + ec.message());
    std::string tmpl = (tree / ".smi-tmp-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw Error("cannot create a temporary folder in '" + tree.string() + "'");
    dir = tmpl;
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
    if (!made_tree.empty() && fs::is_empty(made_tree, ec)) fs::remove(made_tree, ec);
  }
};

struct Project {
  fs::path lockfile;  // ./smi-lock.json
  vm::Lockfile lock;
  bool has_lock = false;
  fs::path tree;
};

Project open_project(const Args& a, bool need_lock) {
  Project p;
  p.lockfile = fs::current_path() / vm::kLockfileName;
  std::error_code ec;
  if (fs::exists(p.lockfile, ec)) {
    p.lock = vm::read_lockfile(p.lockfile);
    p.has_lock = true;
  } else if (need_lock) {
    throw Error("there is no " + std::string(vm::kLockfileName) + " in " + fs::current_path().string() +
                ": run this in the project folder, or make one with smi-lua libs add SOURCE@REF");
  }
  if (!a.libs_into.empty()) p.lock.tree = a.libs_into;
  p.tree = vm::lock_tree(p.lock, p.lockfile);
  return p;
}

std::string short_commit(const std::string& c) { return c.size() == 40 ? c.substr(0, 12) : c; }

/// Each file that differs between what the lockfile says and what is there, one line each.
std::vector<std::string> differences(const std::map<std::string, std::string>& want,
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

/// One library to install: fetched into `staged`, to be renamed to tree/name/version.
struct Planned {
  vm::LockEntry entry;
  std::vector<vm::Requirement> requires_;
  std::map<std::string, std::string> sources;  // the manifest's
  fs::path staged;                             // empty: already locked, nothing to install
  std::string why;                             // "" for what the user asked, else "required by x"
  bool pinned = false;                         // what the user asked for: never swapped for another version
};

vm::LockEntry entry_of(const vm::Fetched& f, const std::string& source) {
  vm::LockEntry e;
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

/// Renames every staged folder into place, all or none (a failure moves back what was moved).
void install_all(const std::vector<std::pair<fs::path, fs::path>>& moves) {
  std::vector<std::pair<fs::path, fs::path>> done;
  for (const auto& [from, to] : moves) {
    std::error_code ec;
    fs::create_directories(to.parent_path(), ec);
    if (!ec) fs::rename(from, to, ec);
    if (ec) {
      for (const auto& [f, t] : done) fs::rename(t, f, ec);
      throw Error("cannot install into '" + to.string() + "': " + ec.message() + "; nothing was installed");
    }
    done.emplace_back(from, to);
  }
}

std::string versions_seen(const std::vector<vm::VersionTag>& tags) {
  std::string s;
  for (const auto& t : tags) s += (s.empty() ? "" : ", ") + (t.tag.empty() ? t.version.text : t.tag);
  return s.empty() ? "none (no tag names a version, like v1.2.0)" : s;
}

/// Resolves the requirements of everything in `plan` (fetching what is missing or too old from
/// the sources the manifests name), until every requirement is met. Greedy: each library gets
/// the highest tagged version that satisfies every requirement on it.
void resolve(std::map<std::string, Planned>& plan, const fs::path& scratch, int& counter) {
  std::map<std::string, std::vector<vm::VersionTag>> tag_cache;
  for (int round = 0; round < 100; ++round) {
    bool changed = false;
    for (const auto& [who, item] : plan) {
      for (const vm::Requirement& r : item.requires_) {
        if (r.name == "smi-lua") continue;
        // every requirement on r.name, from every library planned
        std::vector<std::pair<const Planned*, const vm::Requirement*>> on;
        for (const auto& [n, p] : plan)
          for (const auto& q : p.requires_)
            if (q.name == r.name) on.emplace_back(&p, &q);
        const auto accepts_all = [&](const vm::Version& v) {
          for (const auto& [p, q] : on)
            if (!q->accepts(v)) return false;
          return true;
        };
        const auto have = plan.find(r.name);
        if (have != plan.end() && accepts_all(vm::Version::parse(have->second.entry.version))) continue;
        if (have != plan.end() && have->second.pinned) {
          std::string reqs;
          for (const auto& [p, q] : on)
            if (!q->accepts(vm::Version::parse(have->second.entry.version)))
              reqs += (reqs.empty() ? "" : "; ") + p->entry.name + " " + p->entry.version + " requires '" + q->text + "'";
          throw Error("you asked for " + r.name + " " + have->second.entry.version + ", but " + reqs +
                      "; add a version of " + r.name + " that satisfies it, or first a release of the requiring "
                      "library that accepts " + have->second.entry.version);
        }
        std::string source;
        if (const auto s = item.sources.find(r.name); s != item.sources.end()) source = s->second;
        else if (have != plan.end()) source = have->second.entry.source;
        const std::string asker = who + " " + item.entry.version + " requires '" + r.text + "'";
        if (source.empty())
          throw Error(asker + ", but its " + vm::kManifestName + " names no source for " + r.name +
                      " (sources = {" + r.name + " = \"URL\"}) and smi-lock.json holds none; add it first: "
                      "smi-lua libs add URL@TAG");
        if (!tag_cache.count(source)) tag_cache[source] = vm::version_tags(source, scratch);
        const auto& tags = tag_cache[source];
        const vm::VersionTag* pick = nullptr;
        for (const auto& t : tags)
          if (accepts_all(t.version)) {
            pick = &t;
            break;
          }
        if (!pick) {
          std::string reqs;
          for (const auto& [p, q] : on)
            reqs += (reqs.empty() ? "" : "; ") + p->entry.name + " " + p->entry.version + " requires '" + q->text + "'";
          throw Error("no version of " + r.name + " at " + source + " satisfies every requirement on it (" + reqs +
                      "); versions seen: " + versions_seen(tags) +
                      ". Ask for a release that does, or add releases of the requiring libraries that agree");
        }
        const fs::path dir = scratch / ("lib" + std::to_string(++counter));
        const vm::Fetched f = vm::fetch_library(source, pick->tag, dir, scratch);
        if (f.manifest.name != r.name)
          throw Error(asker + "; the source " + source + (pick->tag.empty() ? "" : " at " + pick->tag) + " holds library '" +
                      f.manifest.name + "', not '" + r.name + "': fix 'sources' in " + who + "'s " + vm::kManifestName);
        Planned p;
        p.entry = entry_of(f, source);
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

}  // namespace

int libs_add(const Args& a, const std::vector<std::string>& args) {
  if (args.size() != 1) {
    std::fprintf(stderr, "usage: smi-lua libs add SOURCE[@REF] [--into DIR]   (SOURCE: a git URL, a folder or a "
                         ".tar.gz from libs pack; REF: a tag, branch or commit)\n");
    return 2;
  }
  const auto [source, ref] = vm::split_source_ref(args[0]);
  Project pr = open_project(a, false);
  Scratch sc(pr.tree);
  std::map<std::string, Planned> plan;
  for (const vm::LockEntry& e : pr.lock.libs) {
    Planned p;
    p.entry = e;
    for (const auto& r : e.requires_) p.requires_.push_back(vm::Requirement::parse(r));
    plan[e.name] = std::move(p);
  }
  int counter = 0;
  const fs::path root_dir = sc.dir / ("lib" + std::to_string(++counter));
  const vm::Fetched root = vm::fetch_library(source, ref, root_dir, sc.dir);
  for (const auto& r : root.manifest.requires_)
    if (r.name == "smi-lua" && !r.accepts(vm::Version::parse_loose(vm::host_version())))
      throw Error(root.manifest.name + " " + root.manifest.version.text + " requires '" + r.text + "', but this is smi-lua " +
                  vm::host_version() + "; use a release of " + root.manifest.name + " made for it");
  Planned p;
  p.entry = entry_of(root, source);
  p.requires_ = root.manifest.requires_;
  p.sources = root.manifest.sources;
  p.staged = root_dir;
  p.pinned = true;
  plan[root.manifest.name] = std::move(p);
  resolve(plan, sc.dir, counter);

  // What is already in the tree at the same version must be the same files.
  std::vector<std::pair<fs::path, fs::path>> moves;
  std::vector<const Planned*> installed, present;
  for (const auto& [name, item] : plan) {
    if (item.staged.empty()) continue;
    const fs::path dest = pr.tree / name / item.entry.version;
    std::error_code ec;
    if (fs::exists(dest, ec)) {
      const auto diff = differences(item.entry.files, vm::hash_folder(dest).files);
      if (!diff.empty())
        throw Error(name + " " + item.entry.version + " is already installed at " + dest.string() +
                    " with other files (" + diff.front() + "); remove it (smi-lua libs remove " + name + "@" +
                    item.entry.version + ") and add again");
      present.push_back(&item);
    } else {
      moves.emplace_back(item.staged, dest);
      installed.push_back(&item);
    }
  }
  install_all(moves);
  for (const auto& [name, item] : plan) pr.lock.put(item.entry);
  vm::write_lockfile(pr.lock, pr.lockfile);
  for (const Planned* item : installed) {
    const auto& e = item->entry;
    std::printf("installed %s %s from %s%s%s into %s%s\n", e.name.c_str(), e.version.c_str(), e.source.c_str(),
                e.ref.empty() ? "" : (" at " + e.ref).c_str(),
                e.commit.empty() ? "" : (" (" + short_commit(e.commit) + ")").c_str(),
                (pr.tree / e.name / e.version).string().c_str(), item->why.empty() ? "" : ("; " + item->why).c_str());
  }
  for (const Planned* item : present)
    std::printf("already installed: %s %s (same files)\n", item->entry.name.c_str(), item->entry.version.c_str());
  std::printf("%s: %zu librar%s locked\n", vm::kLockfileName, pr.lock.libs.size(), pr.lock.libs.size() == 1 ? "y" : "ies");
  return 0;
}

int libs_sync(const Args& a, const std::vector<std::string>& args) {
  if (!args.empty()) {
    std::fprintf(stderr, "usage: smi-lua libs sync [--check] [--into DIR]\n");
    return 2;
  }
  Project pr = open_project(a, true);
  std::vector<std::string> errors;
  std::vector<std::pair<fs::path, fs::path>> moves;
  std::vector<std::string> lines;
  std::unique_ptr<Scratch> sc;
  int counter = 0;
  for (const vm::LockEntry& e : pr.lock.libs) {
    const fs::path dest = pr.tree / e.name / e.version;
    const std::string lib = "library " + e.name + " " + e.version;
    std::error_code ec;
    if (fs::exists(dest, ec)) {
      const auto diff = differences(e.files, vm::hash_folder(dest).files);
      for (const auto& d : diff) errors.push_back(lib + " at " + dest.string() + ": " + d);
      if (diff.empty()) lines.push_back("ok         " + e.name + " " + e.version + " (" + std::to_string(e.files.size()) + " files)");
      continue;
    }
    if (a.libs_check) {
      errors.push_back(lib + " is not installed (no " + dest.string() + "); run smi-lua libs sync");
      continue;
    }
    if (!sc) sc = std::make_unique<Scratch>(pr.tree);
    const fs::path dir = sc->dir / ("lib" + std::to_string(++counter));
    // a git source is fetched at the locked commit, so a moved tag cannot change what is restored;
    // a folder added without a ref is copied again (its commit only says what was checked out)
    const bool plain_folder = e.ref.empty() && vm::source_kind(e.source, "") == vm::SourceKind::folder;
    const std::string at = plain_folder ? "" : e.commit.size() == 40 ? e.commit : e.ref;
    try {
      const vm::Fetched f = vm::fetch_library(e.source, at, dir, sc->dir);
      if (f.manifest.name != e.name || f.manifest.version.text != e.version) {
        errors.push_back(lib + ": " + e.source + " at " + at + " now holds " + f.manifest.name + " " +
                         f.manifest.version.text);
        continue;
      }
      const auto diff = differences(e.files, f.hash.files);
      for (const auto& d : diff) errors.push_back(lib + " fetched from " + e.source + ": " + d);
      const bool moved = !plain_folder && !e.commit.empty() && f.commit != e.commit;
      if (diff.empty() && moved) errors.push_back(lib + ": " + e.source + " resolved to " + f.commit + ", locked " + e.commit);
      if (!diff.empty() || moved) continue;
    } catch (const Error& err) {
      errors.push_back(lib + ": " + err.what());
      continue;
    }
    moves.emplace_back(dir, dest);
    lines.push_back("installed  " + e.name + " " + e.version + " from " + e.source +
                    (e.commit.empty() ? "" : " (" + short_commit(e.commit) + ")"));
  }
  if (!errors.empty()) {
    std::string msg = std::to_string(errors.size()) + " difference" + (errors.size() == 1 ? "" : "s") + " from " +
                      pr.lockfile.string() + (a.libs_check ? "" : "; nothing was installed") + ":";
    for (const auto& e : errors) msg += "\n  " + e;
    msg += "\n(a changed file: remove the library folder and run smi-lua libs sync to restore it)";
    throw Error(msg);
  }
  install_all(moves);
  for (const auto& l : lines) std::printf("%s\n", l.c_str());
  std::printf("%s: %zu librar%s, every file matches its SHA-256\n", vm::kLockfileName, pr.lock.libs.size(),
              pr.lock.libs.size() == 1 ? "y" : "ies");
  return 0;
}

int libs_remove(const Args& a, const std::vector<std::string>& args) {
  if (args.size() != 1) {
    std::fprintf(stderr, "usage: smi-lua libs remove NAME[@VERSION]\n");
    return 2;
  }
  const auto at = args[0].find('@');
  const std::string name = args[0].substr(0, at), version = at == std::string::npos ? "" : args[0].substr(at + 1);
  Project pr = open_project(a, false);
  const vm::LockEntry* e = pr.lock.find(name);
  std::error_code ec;
  if (!version.empty() && (!e || e->version != version)) {  // a side-by-side version the lockfile does not use
    const fs::path dir = pr.tree / name / version;
    if (!fs::exists(dir, ec)) throw Error(name + " " + version + " is not installed (no " + dir.string() + ")");
    fs::remove_all(dir, ec);
    if (fs::is_empty(pr.tree / name, ec)) fs::remove(pr.tree / name, ec);
    std::printf("removed %s %s from %s\n", name.c_str(), version.c_str(), pr.tree.string().c_str());
    return 0;
  }
  if (!e) {
    std::string names;
    for (const auto& l : pr.lock.libs) names += (names.empty() ? "" : ", ") + l.name;
    throw Error("library '" + name + "' is not in " + pr.lockfile.string() + " (it holds: " +
                (names.empty() ? std::string("nothing") : names) + ")");
  }
  for (const auto& other : pr.lock.libs)
    for (const auto& r : other.requires_)
      if (other.name != name && vm::Requirement::parse(r).name == name)
        throw Error(other.name + " " + other.version + " requires '" + r + "': remove " + other.name + " first");
  const std::string ver = e->version;
  fs::remove_all(pr.tree / name / ver, ec);
  if (fs::is_empty(pr.tree / name, ec)) fs::remove(pr.tree / name, ec);
  pr.lock.erase(name);
  vm::write_lockfile(pr.lock, pr.lockfile);
  std::printf("removed %s %s (folder and %s entry)\n", name.c_str(), ver.c_str(), vm::kLockfileName);
  return 0;
}

int libs_outdated(const Args& a, const std::vector<std::string>& args) {
  if (!args.empty()) {
    std::fprintf(stderr, "usage: smi-lua libs outdated\n");
    return 2;
  }
  Project pr = open_project(a, true);
  Scratch sc(pr.tree);
  int unreachable = 0;
  for (const vm::LockEntry& e : pr.lock.libs) {
    std::vector<vm::VersionTag> tags;
    try {
      tags = vm::version_tags(e.source, sc.dir);
    } catch (const Error& err) {
      ++unreachable;
      std::printf("%s %s: cannot check, the source cannot be reached (%s)\n", e.name.c_str(), e.version.c_str(), err.what());
      continue;
    }
    const vm::Version cur = vm::Version::parse(e.version);
    std::string newer;
    for (const auto& t : tags)
      if (vm::compare(t.version, cur) > 0) newer += (newer.empty() ? "" : ", ") + (t.tag.empty() ? t.version.text : t.tag);
    if (newer.empty()) std::printf("%s %s: up to date at %s\n", e.name.c_str(), e.version.c_str(), e.source.c_str());
    else std::printf("%s %s: newer at %s: %s\n", e.name.c_str(), e.version.c_str(), e.source.c_str(), newer.c_str());
  }
  if (unreachable) std::printf("%d source%s could not be reached\n", unreachable, unreachable == 1 ? "" : "s");
  return 0;
}

}  // namespace smi::cli
