// SPDX-License-Identifier: MIT
// A library's name and version are data: the grammars (Semantic Versioning 2.0.0 §9 and §10 for
// prerelease and build metadata; Lua identifiers for names) refuse every path-like text, and
// library_dir / LibraryTree, the one place a library path is made and changed, refuse
// separators, dot-segments, NUL and symbolic links. The valid examples are semver.org's own.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "platform/core/errors.hpp"
#include "vm/library_tree.hpp"
#include "vm/lockfile.hpp"
#include "vm/semver.hpp"

#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace smi::vm;

TEST_CASE("build metadata and prerelease follow semver 2.0.0: dot-separated [0-9A-Za-z-] identifiers") {
  // semver.org §9 and §10 examples
  for (const char* ok : {"1.0.0-alpha", "1.0.0-alpha.1", "1.0.0-0.3.7", "1.0.0-x.7.z.92", "1.0.0-x-y-z.--",
                         "1.0.0-alpha+001", "1.0.0+20130313144700", "1.0.0-beta+exp.sha.5114f85",
                         "1.0.0+21AF26D3----117B344092BD"})
    CHECK_NOTHROW(Version::parse(ok));
  for (const char* bad : {"1.0.0+x/../../../../dir", "1.0.0+x/y", "1.0.0+..", "1.0.0+a..b", "1.0.0+", "1.0.0+.a",
                          "1.0.0+a.", "1.0.0+a\\b", "1.0.0+/abs", "1.0.0+a b", "1.0.0-a/../b", "1.0.0-"})
    CHECK_THROWS_AS(Version::parse(bad), smi::Error);
  CHECK_THROWS_WITH(Version::parse("1.0.0+x/../y"), Catch::Contains("build metadata identifiers use only [0-9A-Za-z-]"));
  CHECK_THROWS_AS(Version::parse(std::string("1.0.0+a\0b", 9)), smi::Error);
}

TEST_CASE("library_dir makes <tree>/<name>/<version> and nothing else") {
  CHECK(library_dir("/t", "unitconv", "1.2.0+build.5") == fs::path("/t/unitconv/1.2.0+build.5"));
  for (const std::string& name : {std::string("a/b"), std::string(".."), std::string("."), std::string("a\\b"),
                                  std::string("/abs"), std::string(""), std::string("x\0y", 3), std::string("1abc")})
    CHECK_THROWS_WITH(library_dir("/t", name, "1.0.0"), Catch::Contains("is not a library name"));
  for (const std::string& v : {std::string("1.0.0+x/../../.."), std::string(".."), std::string("/1.0.0"),
                               std::string("1.0.0\0", 6), std::string("1.0.0/")})
    CHECK_THROWS_AS(library_dir("/t", "ok", v), smi::Error);
}

TEST_CASE("a lockfile's tree counts as the project's only when it lies inside the project folder") {
  CHECK(tree_inside_project("smi-libs"));
  CHECK(tree_inside_project("vendor/smi-libs"));
  CHECK_FALSE(tree_inside_project("/abs/secret"));
  CHECK_FALSE(tree_inside_project("../shared"));
  CHECK_FALSE(tree_inside_project("smi-libs/../../x"));
  CHECK_FALSE(tree_inside_project("."));
  CHECK_FALSE(tree_inside_project(""));
  CHECK_FALSE(tree_inside_project(std::string("a\0b", 3)));
}

TEST_CASE("a library tree never acts through a symbolic link") {
  TempDir t;
  fs::create_directories(t.p / "victim/1.0.0");
  std::ofstream(t.p / "victim/1.0.0/data.txt") << "keep";
  // the tree itself a link
  fs::create_directory_symlink(t.p / "victim", t.p / "linked-tree");
  CHECK_THROWS_WITH(LibraryTree::open(t.p / "linked-tree", false), Catch::Contains("is a symbolic link"));
  // a name folder a link
  const LibraryTree tree = LibraryTree::open(t.p / "smi-libs", true);
  REQUIRE(fs::is_directory(t.p / "smi-libs"));
  fs::create_directory_symlink(t.p / "victim", t.p / "smi-libs/lib");
  CHECK_THROWS_WITH(tree.remove("lib", "1.0.0"), Catch::Contains("symbolic link or not a folder"));
  CHECK_THROWS_WITH(tree.has("lib", "1.0.0"), Catch::Contains("symbolic link or not a folder"));
  // a version folder a link
  fs::create_directories(t.p / "smi-libs/other");
  fs::create_directory_symlink(t.p / "victim/1.0.0", t.p / "smi-libs/other/1.0.0");
  CHECK_THROWS_WITH(tree.remove("other", "1.0.0"), Catch::Contains("symbolic link or not a folder"));
  CHECK(fs::exists(t.p / "victim/1.0.0/data.txt"));
  // install and remove of real folders
  fs::create_directories(t.p / "smi-libs/.stage/x");
  tree.install(t.p / "smi-libs/.stage/x", "good", "1.0.0");
  CHECK(tree.has("good", "1.0.0"));
  tree.remove("good", "1.0.0");
  CHECK_FALSE(fs::exists(t.p / "smi-libs/good"));
}
