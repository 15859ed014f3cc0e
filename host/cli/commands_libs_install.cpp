// SPDX-License-Identifier: MIT
// smi-lua libs add / update / sync / remove / outdated, and the requirements of `smi-lua test`:
// the project's library tree (./smi-libs/<name>/<version>/, or --into DIR, reached through
// vm/library_tree.hpp only), its smi-project.json (what the project asks for) and its
// smi-lock.json (what was resolved), in the current folder.
//
// Everything is fetched into a temporary folder inside the tree first (vm/library_sources.hpp:
// no library code runs), checked (manifest against the tag, registry commit and checksum,
// requirements, hashes against the lockfile), and only then moved into place, so a failure
// leaves nothing half-installed.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

#include "cli/commands.hpp"
#include "platform/core/errors.hpp"
#include "vm/library_resolve.hpp"
#include "vm/library_sources.hpp"
#include "vm/library_tree.hpp"
#include "vm/lockfile.hpp"
#include "vm/project_manifest.hpp"

namespace smi::cli {
namespace fs = std::filesystem;
namespace {

struct Project {
  fs::path lockfile;  // ./smi-lock.json
  vm::Lockfile lock;
  bool has_lock = false;
  fs::path manifest_file;  // ./smi-project.json
  vm::ProjectManifest manifest;
  fs::path tree;      // as the lockfile or --into names it, resolved against the project folder
  double timeout_s = 0;  // --timeout, for each git call
  /// The tree opened for changes (created when `create`): every target is checked in it.
  vm::LibraryTree open_tree(bool create) const {
    const vm::LibraryTree t = vm::LibraryTree::open(tree, create);
    // A tree inside the project is reached through no link at all (the project's own folder).
    const fs::path want = (lockfile.parent_path() / lock.tree).lexically_normal();
    if (t.exists() && vm::tree_inside_project(lock.tree) && t.path() != want)
      throw Error("the library tree '" + want.string() + "' is reached through a symbolic link (it leads to " +
                  t.path().string() + "); a project's library tree is a real folder inside it: replace the link "
                  "by a folder and run smi-lua libs sync");
    return t;
  }
};

Project open_project(const Args& a, bool need_lock) {
  Project p;
  std::error_code ec;
  p.lockfile = fs::weakly_canonical(fs::current_path(), ec) / vm::kLockfileName;
  p.timeout_s = a.cfg.timeout_s;
  p.manifest_file = p.lockfile.parent_path() / vm::kProjectManifestName;
  p.manifest = vm::read_project_manifest(p.manifest_file);
  if (fs::exists(p.lockfile, ec)) {
    p.lock = vm::read_lockfile(p.lockfile);
    p.has_lock = true;
  } else if (need_lock) {
    throw Error("there is no " + std::string(vm::kLockfileName) + " in " + fs::current_path().string() +
                ": run this in the project folder, or make one with smi-lua libs add SOURCE@REF");
  }
  if (!a.libs_into.empty()) {
    p.lock.tree = a.libs_into;
  } else if (!vm::tree_inside_project(p.lock.tree)) {
    // Only the user chooses a tree outside the project; a lockfile cannot send an install or a
    // removal elsewhere.
    throw Error(p.lockfile.string() + " names the library tree '" + p.lock.tree +
                "', outside the project folder; libs changes a tree outside the project only when you name it: "
                "add --into " + p.lock.tree);
  }
  p.tree = vm::lock_tree(p.lock, p.lockfile);
  return p;
}

/// A temporary folder inside the tree (same file system, so installing is a rename), removed
/// when done whatever happened.
struct Scratch {
  vm::LibraryTree tree;
  fs::path dir, made_tree;  // made_tree: the tree, when this created it (removed again if left empty)
  vm::GitPlace place;
  explicit Scratch(const Project& pr) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(pr.tree, ec))) made_tree = pr.tree;
    tree = pr.open_tree(true);
    std::string tmpl = (tree.path() / ".smi-tmp-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw Error("cannot create a temporary folder in '" + tree.path().string() + "'");
    dir = tmpl;
    place = {dir, pr.timeout_s};
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
    if (!made_tree.empty() && fs::is_empty(made_tree, ec)) fs::remove(made_tree, ec);
  }
};

/// One staged folder to move into the tree at name/version; `replace`: a changed copy is there
/// and is removed first (libs sync repairing it).
struct Move {
  fs::path staged;
  std::string name, version;
  bool replace = false;
};

/// Moves every staged folder into place, all or none of the new ones (a failure moves back what
/// was moved; a replaced copy was changed by hand, and is not restored).
void install_all(const vm::LibraryTree& tree, const std::vector<Move>& moves) {
  std::vector<const Move*> done;
  for (const Move& m : moves) {
    try {
      if (m.replace) tree.remove(m.name, m.version);
      tree.install(m.staged, m.name, m.version);
    } catch (const Error& e) {
      std::error_code ec;
      for (const Move* d : done) fs::rename(tree.target(d->name, d->version), d->staged, ec);
      throw Error(std::string(e.what()) + "; nothing was installed");
    }
    done.push_back(&m);
  }
}

std::vector<std::pair<std::string, std::string>> registries_of(const vm::ProjectManifest& m) {
  return {m.registries.begin(), m.registries.end()};
}

/// The project's locked libraries, as a plan in which nothing is fetched again.
std::map<std::string, vm::Planned> locked_plan(const vm::Lockfile& lock) {
  std::map<std::string, vm::Planned> plan;
  for (const vm::LockEntry& e : lock.libs) {
    vm::Planned p;
    p.entry = e;
    for (const auto& r : e.requires_) p.requires_.push_back(vm::Requirement::parse(r));
    plan[e.name] = std::move(p);
  }
  return plan;
}

/// "NAME[@RANGE]" on the command line: a library name (no folder or file of that name here).
struct ByName {
  std::string name;
  vm::Requirement req;  // what to install now
  std::string range;    // what smi-project.json records ("" = "^" + the version installed)
};

std::optional<ByName> parse_by_name(const std::string& arg) {
  const std::size_t at = arg.find('@');
  const std::string name = arg.substr(0, at), spec = at == std::string::npos ? "" : arg.substr(at + 1);
  std::error_code ec;
  // "git@host:path" and "https://user@host/x" are addresses, and an existing folder is a folder
  if (!vm::valid_library_name(name) || spec.find_first_of(":/") != std::string::npos ||
      fs::exists(fs::symlink_status(arg, ec)) || fs::exists(fs::symlink_status(name, ec)))
    return std::nullopt;
  ByName b;
  b.name = name;
  vm::Version v;
  if (spec.empty()) {
    b.req = vm::Requirement::parse(name);
  } else if (vm::tag_version(spec, v)) {  // NAME@1.3.0 (or @v1.3.0): that version; later updates stay compatible
    b.req = vm::Requirement::parse(name + " == " + v.text);
    b.range = "^" + v.text;
  } else {
    b.req = vm::Requirement::parse(name + " " + spec);
    b.range = spec;
  }
  return b;
}

std::string candidates_text(const std::vector<vm::Candidate>& cands) {
  std::string s;
  for (const auto& c : cands) s += (s.empty() ? "" : ", ") + c.version.text;
  return s.empty() ? "none" : s;
}

/// Where versions of `name` are found for this project, and the direct requirement to record.
struct Found {
  std::vector<vm::Candidate> cands;
  std::string where;
  vm::DirectRequirement direct;  // source or registry filled in
};

Found find_versions(const Project& pr, vm::VersionFinder& finder, const std::string& name) {
  Found f;
  const auto d = pr.manifest.requires_.find(name);
  const vm::LockEntry* locked = pr.lock.find(name);
  if (d != pr.manifest.requires_.end() && !d->second.registry.empty()) {
    f.direct.registry = d->second.registry;
    f.cands = finder.in_registries(name, f.direct.registry);
    f.where = "the registry " + f.direct.registry + " (" + pr.manifest.registries.at(f.direct.registry) + ")";
    return f;
  }
  f.direct.source = d != pr.manifest.requires_.end() ? d->second.source : locked ? locked->source : "";
  if (!f.direct.source.empty()) {
    f.cands = finder.at_source(f.direct.source);
    f.where = f.direct.source;
    return f;
  }
  if (!finder.has_registries())
    throw Error("library '" + name + "' has no source recorded in " + std::string(vm::kProjectManifestName) + " or " +
                vm::kLockfileName + ", and the project names no registry; give its address (smi-lua libs add "
                "URL@TAG), or name the team's registry first (smi-lua libs registry NAME URL)");
  f.cands = finder.in_registries(name);
  f.where = "the registries " + finder.registries_text();
  if (f.cands.empty())
    throw Error("no library '" + name + "' is published in " + f.where + "; look for it with smi-lua libs search " +
                name + ", or give its address (smi-lua libs add URL@TAG)");
  for (const auto& [rname, url] : pr.manifest.registries)
    if (url == f.cands.front().registry) f.direct.registry = rname;
  return f;
}

void check_host_version(const vm::Manifest& m) {
  for (const auto& r : m.requires_)
    if (r.name == "smi-lua" && !r.accepts(vm::Version::parse_loose(vm::host_version())))
      throw Error(m.name + " " + m.version.text + " requires '" + r.text + "', but this is smi-lua " +
                  vm::host_version() + "; use a release of " + m.name + " made for it");
}

/// Installs what `plan` fetched (all or nothing), then writes smi-lock.json with every planned
/// library; prints one line each.
void install_plan(Project& pr, Scratch& sc, const std::map<std::string, vm::Planned>& plan) {
  // What is already in the tree at the same version must be the same files.
  std::vector<Move> moves;
  std::vector<const vm::Planned*> installed, present;
  for (const auto& [name, item] : plan) {
    if (item.staged.empty()) continue;
    const fs::path dest = sc.tree.target(name, item.entry.version);
    if (sc.tree.has(name, item.entry.version)) {
      const auto diff = vm::lock_differences(item.entry.files, vm::hash_folder(dest).files);
      if (!diff.empty())
        throw Error(name + " " + item.entry.version + " is already installed at " + dest.string() +
                    " with other files (" + diff.front() + "); remove it (smi-lua libs remove " + name + "@" +
                    item.entry.version + ") and add again");
      present.push_back(&item);
    } else {
      moves.push_back({item.staged, name, item.entry.version});
      installed.push_back(&item);
    }
  }
  install_all(sc.tree, moves);
  for (const auto& [name, item] : plan) pr.lock.put(item.entry);
  vm::write_lockfile(pr.lock, pr.lockfile);
  for (const vm::Planned* item : installed) {
    const auto& e = item->entry;
    std::printf("installed %s %s from %s%s%s into %s%s\n", e.name.c_str(), e.version.c_str(), e.source.c_str(),
                e.ref.empty() ? "" : (" at " + e.ref).c_str(),
                e.commit.empty() ? "" : (" (" + short_commit(e.commit) + ")").c_str(),
                sc.tree.target(e.name, e.version).string().c_str(), item->why.empty() ? "" : ("; " + item->why).c_str());
  }
  for (const vm::Planned* item : present)
    std::printf("already installed: %s %s (same files)\n", item->entry.name.c_str(), item->entry.version.c_str());
  std::printf("%s: %zu librar%s locked\n", vm::kLockfileName, pr.lock.libs.size(), pr.lock.libs.size() == 1 ? "y" : "ies");
}

/// Moves each of `names` to the highest version that its range in smi-project.json and every
/// locked library's requirement on it accept, then resolves and installs what that needs.
void update_names(Project& pr, Scratch& sc, const std::vector<std::string>& names) {
  vm::VersionFinder finder(sc.place, registries_of(pr.manifest));
  std::map<std::string, vm::Planned> plan = locked_plan(pr.lock);
  int counter = 0;
  bool any = false;
  for (const std::string& name : names) {
    std::vector<vm::Requirement> own;
    if (const auto d = pr.manifest.requires_.find(name); d != pr.manifest.requires_.end()) own.push_back(d->second.requirement());
    std::vector<const vm::Requirement*> on;
    for (const auto& r : own) on.push_back(&r);
    for (const auto& [n, p] : plan)
      for (const auto& q : p.requires_)
        if (q.name == name && n != name) on.push_back(&q);
    const Found found = find_versions(pr, finder, name);
    const vm::Candidate* pick = vm::best_candidate(found.cands, on);
    std::string ranges;
    for (const vm::Requirement* r : on) ranges += (ranges.empty() ? "" : ", ") + r->constraint();
    if (!pick)
      throw Error("no version of " + name + " at " + found.where + " satisfies " + ranges + "; versions there: " +
                  candidates_text(found.cands));
    const vm::LockEntry* locked = pr.lock.find(name);
    if (locked && vm::compare(vm::Version::parse(locked->version), pick->version) == 0) {
      std::printf("%s %s: up to date (the highest of %s at %s)\n", name.c_str(), locked->version.c_str(),
                  ranges.empty() ? "any version" : ranges.c_str(), found.where.c_str());
      continue;
    }
    const fs::path dir = sc.dir / ("lib" + std::to_string(++counter));
    const vm::Fetched f = finder.fetch(*pick, name, dir);
    check_host_version(f.manifest);
    std::printf("updating %s %s -> %s\n", name.c_str(), locked ? locked->version.c_str() : "(not locked)",
                f.manifest.version.text.c_str());
    vm::Planned p;
    p.entry = vm::entry_of(f, pick->source);
    p.requires_ = f.manifest.requires_;
    p.sources = f.manifest.sources;
    p.staged = dir;
    p.pinned = true;
    plan[name] = std::move(p);
    any = true;
  }
  if (!any) return;
  vm::resolve(plan, finder, counter);
  install_plan(pr, sc, plan);
}

}  // namespace

int libs_add(const Args& a, const std::vector<std::string>& args) {
  if (args.size() != 1) {
    std::fprintf(stderr, "usage: smi-lua libs add SOURCE[@REF] | NAME[@RANGE] [--into DIR]   (SOURCE: a git URL, a "
                         "folder or a .tar.gz from libs pack; REF: a tag, branch or commit; NAME: a library found at "
                         "its recorded source or in the project's registries; RANGE: 1.2.0, ^1.2 or '>= 1.2, < 2')\n");
    return 2;
  }
  Project pr = open_project(a, false);
  Scratch sc(pr);
  vm::VersionFinder finder(sc.place, registries_of(pr.manifest));
  std::map<std::string, vm::Planned> plan = locked_plan(pr.lock);
  int counter = 0;
  const fs::path root_dir = sc.dir / ("lib" + std::to_string(++counter));
  vm::DirectRequirement direct;
  vm::Fetched root;
  std::string root_source;
  if (const auto by_name = parse_by_name(args[0])) {
    // NAME[@RANGE]: the source recorded in smi-project.json or smi-lock.json, else the registries
    const Found found = find_versions(pr, finder, by_name->name);
    const vm::Candidate* pick = vm::best_candidate(found.cands, {&by_name->req});
    if (!pick)
      throw Error("no version of " + by_name->name + " at " + found.where + " is " + by_name->req.constraint() +
                  "; versions there: " + candidates_text(found.cands));
    root = finder.fetch(*pick, by_name->name, root_dir);
    root_source = pick->source;
    direct = found.direct;
    direct.range = by_name->range.empty() ? "^" + root.manifest.version.text : by_name->range;
  } else {
    const auto [source, ref] = vm::split_source_ref(args[0]);
    root = vm::fetch_library(source, ref, root_dir, sc.place);
    root_source = source;
    direct.source = source;
    direct.range = "^" + root.manifest.version.text;
  }
  direct.name = root.manifest.name;
  check_host_version(root.manifest);
  vm::Planned p;
  p.entry = vm::entry_of(root, root_source);
  p.requires_ = root.manifest.requires_;
  p.sources = root.manifest.sources;
  p.staged = root_dir;
  p.pinned = true;
  plan[root.manifest.name] = std::move(p);
  vm::resolve(plan, finder, counter);
  install_plan(pr, sc, plan);
  pr.manifest.requires_[direct.name] = direct;
  vm::write_project_manifest(pr.manifest, pr.manifest_file);
  std::printf("%s: %s %s\n", vm::kProjectManifestName, direct.name.c_str(),
              direct.range.empty() ? "any version" : direct.range.c_str());
  return 0;
}

int libs_update(const Args& a, const std::vector<std::string>& args) {
  if (args.size() > 1) {
    std::fprintf(stderr, "usage: smi-lua libs update [NAME]   (moves within the ranges of smi-project.json)\n");
    return 2;
  }
  Project pr = open_project(a, true);
  if (!pr.manifest.exists)
    throw Error("there is no " + std::string(vm::kProjectManifestName) + " in " + pr.lockfile.parent_path().string() +
                ": libs update moves each library within the range the project asks for, which smi-lua libs add "
                "records there; add the libraries again with libs add NAME or URL");
  std::vector<std::string> names;
  if (!args.empty()) {
    if (!pr.manifest.requires_.count(args[0]) && !pr.lock.find(args[0]))
      throw Error("library '" + args[0] + "' is neither in " + pr.manifest_file.string() + " nor in " +
                  pr.lockfile.string() + "; add it with smi-lua libs add " + args[0]);
    names.push_back(args[0]);
  } else {
    for (const auto& [name, d] : pr.manifest.requires_) names.push_back(name);
  }
  Scratch sc(pr);
  update_names(pr, sc, names);
  return 0;
}

// long: one pass in the order a user reads its report: what the manifest asks and the lock lacks is
// resolved first, then each locked library is checked and repaired against the same lock, and the
// errors of all of them are listed together.
int libs_sync(const Args& a, const std::vector<std::string>& args) {
  if (!args.empty()) {
    std::fprintf(stderr, "usage: smi-lua libs sync [--check] [--into DIR]\n");
    return 2;
  }
  Project pr = open_project(a, !vm::read_project_manifest(fs::current_path() / vm::kProjectManifestName).exists);
  std::vector<std::string> errors;
  // smi-project.json says what the project asks for: a requirement the lockfile does not meet
  // (added or changed there by hand or by a teammate) is resolved first, as libs update would.
  std::vector<std::string> unmet;
  for (const auto& [name, d] : pr.manifest.requires_) {
    const vm::LockEntry* e = pr.lock.find(name);
    if (e && d.requirement().accepts(vm::Version::parse(e->version))) continue;
    if (a.libs_check)
      errors.push_back(pr.manifest_file.string() + " asks for " + name + " " +
                       (d.range.empty() ? std::string("(any version)") : d.range) + ", but " + vm::kLockfileName +
                       (e ? " holds " + e->version : std::string(" does not hold it")) + "; run smi-lua libs sync");
    else
      unmet.push_back(name);
  }
  if (!unmet.empty()) {
    Scratch resolving(pr);
    update_names(pr, resolving, unmet);
  }
  const vm::LibraryTree tree = pr.open_tree(false);
  std::vector<Move> moves;
  std::vector<std::string> lines;
  std::unique_ptr<Scratch> sc;
  int counter = 0;
  for (const vm::LockEntry& e : pr.lock.libs) {
    const std::string lib = "library " + e.name + " " + e.version;
    bool replace = false;
    if (tree.has(e.name, e.version)) {
      const fs::path dest = tree.target(e.name, e.version);
      const auto diff = vm::lock_differences(e.files, vm::hash_folder(dest).files);
      if (diff.empty()) {
        lines.push_back("ok         " + e.name + " " + e.version + " (" + std::to_string(e.files.size()) + " files)");
        continue;
      }
      if (a.libs_check) {
        for (const auto& d : diff) errors.push_back(lib + " at " + dest.string() + ": " + d);
        continue;
      }
      // A changed copy is fetched again from its source and replaces the folder.
      for (const auto& d : diff) lines.push_back("repairing  " + e.name + " " + e.version + ": " + d);
      replace = true;
    } else if (a.libs_check) {
      errors.push_back(lib + " is not installed (no " + (pr.tree / e.name / e.version).string() + "); run smi-lua libs sync");
      continue;
    }
    if (!sc) sc = std::make_unique<Scratch>(pr);
    const fs::path dir = sc->dir / ("lib" + std::to_string(++counter));
    // a git source is fetched at the locked commit, so a moved tag cannot change what is restored;
    // a folder added without a ref is copied again (its commit only says what was checked out)
    const bool plain_folder = e.ref.empty() && vm::source_kind(e.source, "") == vm::SourceKind::folder;
    const std::string at = plain_folder ? "" : e.commit.size() == 40 ? e.commit : e.ref;
    try {
      const vm::Fetched f = vm::fetch_library(e.source, at, dir, sc->place);
      if (f.manifest.name != e.name || f.manifest.version.text != e.version) {
        errors.push_back(lib + ": " + e.source + " at " + at + " now holds " + f.manifest.name + " " +
                         f.manifest.version.text);
        continue;
      }
      const auto diff = vm::lock_differences(e.files, f.hash.files);
      for (const auto& d : diff) errors.push_back(lib + " fetched from " + e.source + ": " + d);
      const bool moved = !plain_folder && !e.commit.empty() && f.commit != e.commit;
      if (diff.empty() && moved) errors.push_back(lib + ": " + e.source + " resolved to " + f.commit + ", locked " + e.commit);
      if (!diff.empty() || moved) continue;
    } catch (const Error& err) {
      errors.push_back(lib + ": " + err.what());
      continue;
    }
    moves.push_back({dir, e.name, e.version, replace});
    lines.push_back((replace ? "restored   " : "installed  ") + e.name + " " + e.version + " from " + e.source +
                    (e.commit.empty() ? "" : " (" + short_commit(e.commit) + ")"));
  }
  if (!errors.empty()) {
    std::string msg = std::to_string(errors.size()) + " difference" + (errors.size() == 1 ? "" : "s") + " from " +
                      pr.lockfile.string() + (a.libs_check ? "" : "; nothing was installed") + ":";
    for (const auto& e : errors) msg += "\n  " + e;
    msg += a.libs_check ? "\n(smi-lua libs sync restores each library from its source)"
                        : "\n(the source no longer holds the locked files: restore it, or add the library again)";
    throw Error(msg);
  }
  if (sc) install_all(sc->tree, moves);
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
  const vm::LibraryTree tree = pr.open_tree(false);
  const vm::LockEntry* e = pr.lock.find(name);
  if (!version.empty() && (!e || e->version != version)) {  // a side-by-side version the lockfile does not use
    const fs::path dir = vm::library_dir(pr.tree, name, version);  // the name and version grammar, first
    if (!tree.has(name, version)) throw Error(name + " " + version + " is not installed (no " + dir.string() + ")");
    tree.remove(name, version);
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
  if (tree.exists()) tree.remove(name, ver);
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
  Scratch sc(pr);
  int unreachable = 0;
  for (const vm::LockEntry& e : pr.lock.libs) {
    std::vector<vm::VersionTag> tags;
    try {
      tags = vm::version_tags(e.source, sc.place);
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

namespace smi::cli {

std::string test_dependencies(const Args& a, const fs::path& dir, const fs::path& work) {
  std::error_code ec;
  Project pr;
  pr.lockfile = fs::weakly_canonical(fs::absolute(work, ec), ec) / vm::kLockfileName;
  pr.tree = pr.lockfile.parent_path() / vm::kTreeName;
  pr.timeout_s = a.cfg.timeout_s;
  // Met already by the --lib folders, or by what an earlier run installed?
  std::vector<vm::LibraryRoot> roots = {{dir.string(), "the library tested"}};
  for (const auto& d : a.cfg.lib_dirs) roots.push_back({d, "--lib"});
  if (vm::LibrarySet::discover(roots).problems().empty()) return "";
  if (fs::exists(pr.lockfile, ec)) {
    pr.lock = vm::read_lockfile(pr.lockfile);
    pr.has_lock = true;
    const vm::ProjectLibraries installed = vm::project_libraries(pr.lockfile.parent_path());
    if (vm::LibrarySet::discover(roots, &installed).problems().empty()) return pr.tree.string();
  }
  const vm::Manifest m = vm::read_library_folder(dir);
  fs::create_directories(pr.lockfile.parent_path());
  std::printf("resolving what %s %s requires (from its sources) into %s\n", m.name.c_str(), m.version.text.c_str(),
              pr.tree.string().c_str());
  Scratch sc(pr);
  vm::VersionFinder finder(sc.place, {});
  std::map<std::string, vm::Planned> plan = locked_plan(pr.lock);
  vm::Planned self;
  self.entry.name = m.name;
  self.entry.version = m.version.text;
  self.requires_ = m.requires_;
  self.sources = m.sources;
  self.pinned = true;
  plan[m.name] = std::move(self);
  int counter = 0;
  vm::resolve(plan, finder, counter);
  plan.erase(m.name);
  install_plan(pr, sc, plan);
  return pr.tree.string();
}

}  // namespace smi::cli
