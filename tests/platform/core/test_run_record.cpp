// SPDX-License-Identifier: MIT
// The run record (provenance): files hashed from the descriptor read (FIPS 180-2 "abc"
// vector), a Lua record upgrading a data one, a file read twice with other contents marked,
// outputs excluded, files over 1 GB identified by size and mtime (a sparse file: no gigabyte
// written), the read counter for per-step inputs.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "platform/core/run_record.hpp"

using smi::RunRecord;
namespace fs = std::filesystem;

namespace {
const char* const kAbc = "sha256:ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";

struct TempDir {
  fs::path dir;
  TempDir() {
    char tmpl[] = "/tmp/smi_run_record_XXXXXX";
    dir = ::mkdtemp(tmpl);
  }
  ~TempDir() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  }
};

void read_into(RunRecord& r, const std::string& kind, const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  REQUIRE(fd >= 0);
  r.file(kind, path, fd);
  ::close(fd);
}
}  // namespace

TEST_CASE("a file read is recorded with the SHA-256 of its bytes") {
  TempDir t;
  RunRecord r;
  const std::string p = t.write("data.csv", "abc");
  read_into(r, "data", p);
  const auto files = r.files();
  REQUIRE(files.count(p) == 1);
  CHECK(files.at(p).digest.hash == kAbc);
  CHECK(files.at(p).digest.size == 3);
  CHECK_FALSE(files.at(p).digest.large);
  CHECK(files.at(p).kind == "data");
  CHECK(smi::digest_path(p).hash == kAbc);
}

TEST_CASE("a module read as data first is recorded as Lua; a changed re-read is marked") {
  TempDir t;
  RunRecord r;
  const std::string p = t.write("helpers.lua", "abc");
  read_into(r, "data", p);
  read_into(r, "lua", p);
  CHECK(r.files().at(p).kind == "lua");
  CHECK_FALSE(r.files().at(p).changed_during_run);
  t.write("helpers.lua", "abcd");
  read_into(r, "lua", p);
  CHECK(r.files().at(p).changed_during_run);
  CHECK(r.files().at(p).digest.size == 4);
}

TEST_CASE("reads under an excluded folder are outputs, not inputs") {
  TempDir t;
  RunRecord r;
  fs::create_directories(t.dir / "out");
  const std::string inside = t.write("out/results.json", "{}");
  const std::string outside = t.write("prior.lua", "abc");
  read_into(r, "data", outside);
  r.exclude_roots.push_back((t.dir / "out").string());
  read_into(r, "data", inside);
  CHECK(r.files().count(inside) == 0);
  r.exclude(outside);  // a results file outside --out, read before the study said so
  CHECK(r.files().empty());
}

TEST_CASE("a file over 1 GB is identified by size and mtime, not hashed") {
  TempDir t;
  const std::string p = (t.dir / "big.bin").string();
  { std::ofstream(p).put('x'); }
  fs::resize_file(p, smi::kLargeFileBytes + 1);  // sparse: nothing is written
  const smi::FileDigest d = smi::digest_path(p);
  CHECK(d.large);
  CHECK(d.hash.empty());
  CHECK(d.size == smi::kLargeFileBytes + 1);
  CHECK(d.mtime > 0);
}

TEST_CASE("the read counter tells which files were read after a mark") {
  TempDir t;
  RunRecord r;
  const std::string a = t.write("a.csv", "1"), b = t.write("b.csv", "2");
  read_into(r, "data", a);
  const std::uint64_t mark = r.seq();
  read_into(r, "data", b);
  CHECK(r.files().at(a).seq <= mark);
  CHECK(r.files().at(b).seq > mark);
  read_into(r, "data", a);  // read again after the mark: counts as read after it
  CHECK(r.files().at(a).seq > mark);
}
