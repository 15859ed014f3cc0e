// SPDX-License-Identifier: MIT
// The Lua-free parts of `smi-lua libs`: the ustar+gzip reader/writer (checked against
// the system's tar, a peer implementation), the lockfile's checksums, SOURCE@REF splitting,
// version tags, and the manifest's `sources` field.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "platform/core/errors.hpp"
#include "vm/folder_hash.hpp"
#include "vm/library_sources.hpp"
#include "vm/lockfile.hpp"
#include "vm/manifest.hpp"
#include "vm/tar_gz.hpp"

#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace smi::vm;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("tar.gz: what we write, the system's tar reads, and long names survive both ways") {
  TempDir t;
  const std::string deep = "lib-1.0.0/" + std::string(80, 'd') + "/" + std::string(90, 'f') + ".lua";
  std::vector<TarMember> ms = {{"lib-1.0.0", true, false, ""},
                               {"lib-1.0.0/" + std::string(80, 'd'), true, false, ""},
                               {deep, false, false, "return 1\n"},
                               {"lib-1.0.0/run.sh", false, true, "#!/bin/sh\n"},
                               {"lib-1.0.0/empty.lua", false, false, ""}};
  const fs::path file = t.p / "a.tar.gz";
  write_tar_gz(file, ms);
  const auto back = read_tar_gz(file);
  REQUIRE(back.size() == ms.size());
  for (std::size_t i = 0; i < ms.size(); ++i) {
    CHECK(back[i].path == ms[i].path);
    CHECK(back[i].is_dir == ms[i].is_dir);
    CHECK(back[i].data == ms[i].data);
    CHECK(back[i].executable == ms[i].executable);
  }
  fs::create_directories(t.p / "x");
  const std::string cmd = "tar -xzf '" + file.string() + "' -C '" + (t.p / "x").string() + "'";
  REQUIRE(std::system(cmd.c_str()) == 0);
  CHECK(slurp(t.p / "x" / deep) == "return 1\n");
  CHECK((fs::status(t.p / "x" / "lib-1.0.0/run.sh").permissions() & fs::perms::owner_exec) != fs::perms::none);
  // byte-reproducible
  write_tar_gz(t.p / "b.tar.gz", ms);
  CHECK(slurp(file) == slurp(t.p / "b.tar.gz"));
}

TEST_CASE("tar.gz: a name too long for ustar, and input that is no archive, are clear errors") {
  TempDir t;
  CHECK_THROWS_WITH(write_tar_gz(t.p / "a.tar.gz", {{std::string(300, 'n'), false, false, "x"}}),
                    Catch::Contains("too long for a tar archive"));
  std::ofstream(t.p / "junk.tar.gz") << "not gzip at all";
  CHECK_THROWS_WITH(read_tar_gz(t.p / "junk.tar.gz"), Catch::Contains("is not a gzip-compressed archive"));
}

TEST_CASE("lockfile: written then read back; a changed digest or a dropped entry is refused by name") {
  TempDir t;
  Lockfile l;
  LockEntry e{"unitconv", "2.0.0", "file:///x/unitconv", "v2.0.0", std::string(40, 'a'), {"smi-lua >= 0.1"}, "", {}};
  e.files = {{"init.lua", std::string(64, 'b')}, {"smi-lib.lua", std::string(64, 'c')}};
  e.hash = combine_file_hashes(e.files);
  l.put(e);
  LockEntry f = e;
  f.name = "refcrit";
  f.requires_ = {"unitconv >= 2"};
  l.put(f);
  const fs::path file = t.p / kLockfileName;
  write_lockfile(l, file);
  const Lockfile back = read_lockfile(file);
  REQUIRE(back.libs.size() == 2);
  CHECK(back.libs[0].name == "refcrit");  // sorted by name
  CHECK(back.find("unitconv")->files == e.files);
  CHECK(back.find("refcrit")->requires_ == f.requires_);

  std::string text = slurp(file);
  const std::size_t at = text.find(std::string(64, 'b'));
  text[at] = 'd';
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
  CHECK_THROWS_WITH(read_lockfile(file), Catch::Contains("library 'refcrit' 2.0.0 was edited by hand"));

  Lockfile one;
  one.put(e);
  write_lockfile(one, file);
  std::string single = slurp(file);
  write_lockfile(l, file);
  // the two-entry file with the one-entry file's top checksum (the first key: the writer sorts
  // keys): an entry was added by hand
  const auto top_sum_at = [](const std::string& s) { return s.find("\"checksum\": \"") + 13; };
  std::string two = slurp(file);
  two.replace(top_sum_at(two), 71, single.substr(top_sum_at(single), 71));
  std::ofstream(file, std::ios::binary | std::ios::trunc) << two;
  CHECK_THROWS_WITH(read_lockfile(file), Catch::Contains("a library entry was added or removed"));
}

TEST_CASE("SOURCE@REF and version tags") {
  using P = std::pair<std::string, std::string>;
  CHECK(split_source_ref("https://git.example.org/a/refcrit.git@v1.2.0") == P{"https://git.example.org/a/refcrit.git", "v1.2.0"});
  CHECK(split_source_ref("git@host:team/refcrit.git") == P{"git@host:team/refcrit.git", ""});
  CHECK(split_source_ref("git@host:team/refcrit.git@main") == P{"git@host:team/refcrit.git", "main"});
  CHECK(split_source_ref("https://user@host/refcrit") == P{"https://user@host/refcrit", ""});
  CHECK(split_source_ref("refcrit.git@feature/x") == P{"refcrit.git", "feature/x"});
  Version v;
  CHECK(tag_version("v1.2.0", v));
  CHECK(v.text == "1.2.0");
  CHECK(tag_version("2.0.0-rc.1", v));
  CHECK_FALSE(tag_version("release-1", v));
  CHECK_FALSE(tag_version("v1.2", v));
}

TEST_CASE("manifest: sources maps library names to where libs add fetches them") {
  const Manifest m = parse_manifest("name = 'a'\nversion = '1.0.0'\nrequires = {'b >= 1'}\n"
                                    "sources = {b = 'https://git.example.org/b.git'}\n",
                                    "smi-lib.lua");
  CHECK(m.sources.at("b") == "https://git.example.org/b.git");
  CHECK_THROWS_WITH(parse_manifest("name = 'a'\nversion = '1.0.0'\nsources = {'https://x'}\n", "smi-lib.lua"),
                    Catch::Contains("field 'sources' must map library names"));
  CHECK_THROWS_WITH(parse_manifest("name = 'a'\nversion = '1.0.0'\nsources = 'https://x'\n", "smi-lib.lua"),
                    Catch::Contains("field 'sources' must be a table"));
}
