// SPDX-License-Identifier: MIT
// The Lua-free parts of library sharing: semver precedence (checked against the ordering
// example of semver.org §11), requirements, manifests read safely, the git commit read from
// .git files (checked against `git rev-parse HEAD`), and folder hashes (FIPS 180-2 vectors).
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "platform/core/errors.hpp"
#include "vm/folder_hash.hpp"
#include "vm/git_commit.hpp"
#include "vm/libraries.hpp"
#include "vm/manifest.hpp"
#include "vm/semver.hpp"

#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace smi::vm;

namespace {

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

std::string sh(const std::string& cmd) {
  std::string out;
  if (FILE* f = ::popen(cmd.c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, f)) out += buf;
    ::pclose(f);
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

std::string git(const fs::path& dir, const std::string& args) {
  return sh("git -C '" + dir.string() + "' -c user.name=t -c user.email=t@x -c init.defaultBranch=main " + args +
            " 2>/dev/null");
}

}  // namespace

TEST_CASE("semver precedence follows the semver.org 2.0.0 example chain") {
  const char* chain[] = {"1.0.0-alpha", "1.0.0-alpha.1", "1.0.0-alpha.beta", "1.0.0-beta", "1.0.0-beta.2",
                         "1.0.0-beta.11", "1.0.0-rc.1", "1.0.0", "1.0.1", "1.1.0", "2.0.0", "10.0.0"};
  for (std::size_t i = 0; i + 1 < std::size(chain); ++i) {
    INFO(chain[i] << " < " << chain[i + 1]);
    CHECK(compare(Version::parse(chain[i]), Version::parse(chain[i + 1])) < 0);
    CHECK(compare(Version::parse(chain[i + 1]), Version::parse(chain[i])) > 0);
  }
  CHECK(compare(Version::parse("1.2.3+build.7"), Version::parse("1.2.3")) == 0);  // build metadata ignored
}

TEST_CASE("versions that are not MAJOR.MINOR.PATCH are refused with the reason") {
  CHECK_THROWS_WITH(Version::parse("1.2"), Catch::Contains("not MAJOR.MINOR.PATCH"));
  CHECK_THROWS_WITH(Version::parse("1.x.0"), Catch::Contains("minor part 'x'"));
  CHECK_THROWS_WITH(Version::parse("01.2.0"), Catch::Contains("leading zero"));
  CHECK(Version::parse_loose("1.2").minor == 2);
}

TEST_CASE("requirements accept exactly the versions their bounds allow") {
  const Requirement r = Requirement::parse("kdetools >= 1.2, < 2");
  CHECK(r.name == "kdetools");
  CHECK_FALSE(r.accepts(Version::parse("1.1.9")));
  CHECK(r.accepts(Version::parse("1.2.0")));
  CHECK(r.accepts(Version::parse("1.9.3")));
  CHECK_FALSE(r.accepts(Version::parse("2.0.0")));
  CHECK_FALSE(r.accepts(Version::parse("1.2.0-rc.1")));  // a prerelease precedes its release
  const Requirement caret = Requirement::parse("x ^1.4");
  CHECK(caret.accepts(Version::parse("1.7.0")));
  CHECK_FALSE(caret.accepts(Version::parse("1.3.0")));
  CHECK_FALSE(caret.accepts(Version::parse("2.0.0")));
  CHECK(Requirement::parse("x").accepts(Version::parse("0.0.1")));
  CHECK(Requirement::parse("x == 1.0.0").accepts(Version::parse("1.0.0")));
  CHECK_THROWS_WITH(Requirement::parse("x 1.2"), Catch::Contains("has no comparison operator"));
  CHECK_THROWS_WITH(Requirement::parse(">= 1.2"), Catch::Contains("does not start with a library name"));
  CHECK_THROWS_WITH(Requirement::parse("x =< 1.2"), Catch::Contains("unknown operator '=<'"));
}

TEST_CASE("a manifest is read as data, in either form") {
  const Manifest a = parse_manifest("name = 'refcrit'\nversion = '1.2.0'\nrequires = {'kde >= 1.0'}\n", "a/smi-lib.lua");
  CHECK(a.name == "refcrit");
  CHECK(a.version.minor == 2);
  REQUIRE(a.requires_.size() == 1);
  CHECK(a.requires_[0].name == "kde");
  const Manifest b = parse_manifest("return {name = 'b', version = '0.1.0', description = 'd'}", "b/smi-lib.lua");
  CHECK(b.description == "d");
}

TEST_CASE("a manifest cannot run code, loop forever, exhaust memory or carry typos") {
  CHECK_THROWS_WITH(parse_manifest("name = 'x' version = '1.0.0' os.exit(3)", "m/smi-lib.lua"),
                    Catch::Contains("m/smi-lib.lua' failed") && Catch::Contains("global 'os'"));
  CHECK_THROWS_WITH(parse_manifest("while true do end", "m/smi-lib.lua"), Catch::Contains("more than"));
  CHECK_THROWS_WITH(parse_manifest("local s = 'x' for i = 1, 40 do s = s .. s end", "m/smi-lib.lua"),
                    Catch::Contains("failed"));
  CHECK_THROWS_WITH(parse_manifest("name='x' version='1.0.0' require={'y'}", "m/smi-lib.lua"),
                    Catch::Contains("unknown field 'require'") && Catch::Contains("did you mean 'requires'"));
  CHECK_THROWS_WITH(parse_manifest("name='x-y' version='1.0.0'", "m/smi-lib.lua"),
                    Catch::Contains("not a valid library name"));
  CHECK_THROWS_WITH(parse_manifest("name='x' version='1.0'", "m/smi-lib.lua"), Catch::Contains("field 'version'"));
  CHECK_THROWS_WITH(parse_manifest("name='x' version='1.0.0' requires={'y 2'}", "m/smi-lib.lua"),
                    Catch::Contains("requires[1]"));
  CHECK_THROWS_WITH(parse_manifest("\27Lua", "m/smi-lib.lua"), Catch::Contains("does not load"));
}

TEST_CASE("the git commit is read from .git files as git itself reports it") {
  REQUIRE_FALSE(sh("git --version").empty());  // the tests need git to make real checkouts
  TempDir t;
  const fs::path repo = t.p / "lib";
  write(repo / "init.lua", "return {}\n");
  CHECK(git_info(repo).commit.empty());  // not a checkout
  git(repo, "init -q");
  CHECK(git_info(repo).commit.empty());  // a checkout without a commit yet
  git(repo, "add -A");
  git(repo, "commit -q -m one");
  const std::string head1 = git(repo, "rev-parse HEAD");
  REQUIRE(head1.size() == 40);
  CHECK(git_info(repo).commit == head1);        // loose ref
  CHECK(git_info(repo).branch == "main");
  CHECK(git_info(repo / "sub").commit == head1);  // a folder inside a checkout
  git(repo, "pack-refs --all");
  CHECK(git_info(repo).commit == head1);        // packed-refs
  write(repo / "two.lua", "return 2\n");
  git(repo, "add -A");
  git(repo, "commit -q -m two");
  const std::string head2 = git(repo, "rev-parse HEAD");
  CHECK(git_info(repo).commit == head2);
  git(repo, "checkout -q --detach " + head1);
  CHECK(git_info(repo).commit == head1);        // detached HEAD
  CHECK(git_info(repo).branch.empty());
}

TEST_CASE("a folder hash holds standard SHA-256 file digests and sees every change") {
  TempDir t;
  write(t.p / "a.txt", "abc");
  write(t.p / "sub/b.lua", "");
  write(t.p / ".git/HEAD", "ref: refs/heads/main\n");  // left out
  write(t.p / "smi-out/x/results.json", "{}");         // counted: a library may load any of its files
  const FolderHash h = hash_folder(t.p);
  REQUIRE(h.files.size() == 3);
  CHECK(h.files.at("smi-out/x/results.json") == "44136fa355b3678a1146ad16f7e8649e94fb4fc21fe77e8310c060f61caaff8a");
  CHECK(h.files.at("a.txt") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");  // FIPS 180-2
  CHECK(h.files.at("sub/b.lua") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(h.digest.rfind("sha256:", 0) == 0);
  CHECK(h.digest == combine_file_hashes(h.files));
  write(t.p / ".git/HEAD", "ref: refs/heads/other\n");
  CHECK(hash_folder(t.p).digest == h.digest);
  write(t.p / "a.txt", "abd");
  CHECK(hash_folder(t.p).digest != h.digest);
  write(t.p / "a.txt", "abc");
  fs::rename(t.p / "sub/b.lua", t.p / "sub/c.lua");  // same bytes, another name
  CHECK(hash_folder(t.p).digest != h.digest);
  fs::rename(t.p / "sub/c.lua", t.p / "sub/b.lua");
  write(t.p / "smi-out/payload.lua", "return 1");  // code added under smi-out/ changes the hash
  CHECK(hash_folder(t.p).digest != h.digest);
}

TEST_CASE("the library set finds libraries, one version each, and checks requirements") {
  TempDir t;
  write(t.p / "a/kde/smi-lib.lua", "name='kde' version='1.1.0'");
  write(t.p / "a/ref/smi-lib.lua", "name='ref' version='2.0.0' requires={'kde >= 1.2'}");
  write(t.p / "a/plain/mod.lua", "return 1");  // no manifest: not a library
  const std::string a = (t.p / "a").string();
  LibrarySet s = LibrarySet::discover(library_roots({a}, nullptr));
  REQUIRE(s.all().size() == 2);
  CHECK(s.all()[0].name() == "kde");
  auto p = s.problems();
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0], Catch::Contains("ref 2.0.0") && Catch::Contains("requires 'kde >= 1.2'") &&
                       Catch::Contains("kde 1.1.0 at") && Catch::Contains("does not satisfy >= 1.2"));
  CHECK_THROWS_WITH(s.check(), Catch::Contains("the study was not started"));

  write(t.p / "b/kde/smi-lib.lua", "name='kde' version='1.3.0'");
  s = LibrarySet::discover(library_roots({a}, (t.p / "b").c_str()));
  p = s.problems();
  REQUIRE(p.size() == 2);
  CHECK_THAT(p[0], Catch::Contains("two copies of library 'kde'") && Catch::Contains("1.1.0") &&
                       Catch::Contains("1.3.0") && Catch::Contains("SMI_PATH"));

  s = LibrarySet::discover(library_roots({(t.p / "a/ref").string(), (t.p / "b").string()}, nullptr));
  CHECK(s.problems().empty());  // a --lib entry may be a library folder itself

  s = LibrarySet::discover(library_roots({(t.p / "a/ref").string()}, nullptr));
  p = s.problems();
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0], Catch::Contains("no library 'kde' is on the library path") && Catch::Contains("--lib"));

  write(t.p / "c/h/smi-lib.lua", "name='h' version='1.0.0' requires={'smi-lua >= 999'}");
  s = LibrarySet::discover(library_roots({(t.p / "c").string()}, nullptr));
  p = s.problems();
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0], Catch::Contains(std::string("this is smi-lua ") + host_version()));
}
