// SPDX-License-Identifier: MIT
// The SQLite evaluation store: exact round trip, success never overwritten by a failure,
// read-only sharing, timings.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <unistd.h>

#include "platform/eval/store.hpp"

#include <fstream>
#include <sqlite3.h>

using namespace smi::eval;
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const char* name) {
  std::string top = "smi-eval-test-";  // (not literal + string: GCC 12 warns falsely, PR 105329)
  top += std::to_string(::getpid());
  const fs::path d = fs::temp_directory_path() / top / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
Record rec(const std::string& key, bool ok, double d) {
  // std::string(...) moved in: assigning short literals trips GCC 12's false -Wrestrict (PR 105329).
  Record r;
  r.key = key;
  r.model = std::string("m");
  r.program = std::string("solver");
  r.version = std::string("1");
  r.inputs = {{"x", 0.1}, {"y", 1e-300}};
  if (ok) r.outputs = {{"f", 1.0 / 3.0}, {"g", -2.5e17}};
  r.ok = ok;
  r.reason = std::string(ok ? "" : "exit status 1");
  r.duration = d;
  return r;
}
}  // namespace

TEST_CASE("records round-trip exactly and failures never replace successes") {
  const fs::path dir = fresh_dir("roundtrip");
  const std::string path = (dir / "e.sqlite").string();
  {
    Store s(path, false);
    s.put(rec("k1", true, 2.0));
    s.put(rec("k2", false, 4.0));
    s.put(rec("k1", false, 9.0));  // a later failure of the same deck
    auto r1 = s.find("k1");
    REQUIRE(r1);
    CHECK(r1->ok);
    CHECK(r1->outputs[0].second == 1.0 / 3.0);
    CHECK(r1->outputs[1].second == -2.5e17);
    CHECK(r1->inputs[1].second == 1e-300);
    auto r2 = s.find("k2");
    REQUIRE(r2);
    CHECK_FALSE(r2->ok);
    CHECK(r2->reason == "exit status 1");
    s.put(rec("k2", true, 6.0));  // a later success replaces the failure
    CHECK(s.find("k2")->ok);
    CHECK_FALSE(s.find("k3"));
    const Timing t = s.timing("solver", "1");
    CHECK(t.count == 2);
    CHECK(t.mean == Approx(4.0));
  }
  Store ro(path, true);
  CHECK(ro.count() == 2);
  CHECK(ro.find("k1")->ok);
  CHECK_THROWS_WITH(ro.put(rec("k9", true, 1)), Catch::Contains("read-only"));
  CHECK_THROWS_WITH(Store((dir / "missing.sqlite").string(), true), Catch::Contains("missing.sqlite"));
}

TEST_CASE("values encode in shortest round-trip text, NaN included") {
  const NamedValues v = {{"a", 0.1}, {"b", std::numeric_limits<double>::quiet_NaN()}, {"c", -0.0}};
  const NamedValues back = decode_values(encode_values(v));
  REQUIRE(back.size() == 3);
  CHECK(back[0].second == 0.1);
  CHECK(std::isnan(back[1].second));
  CHECK(std::signbit(back[2].second));
  CHECK(encode_values({{"a", 0.1}}) == "a\t0.1\n");
}

// SQLite's own words ("disk I/O error", "no such column: program") named no fix.
TEST_CASE("a store path that is a folder, a foreign table or not a database: the message names the fix") {
  const fs::path d = fresh_dir("messages");
  for (bool ro : {false, true})
    CHECK_THROWS_WITH(Store(d.string(), ro), Catch::Contains("is a folder; a store is one SQLite file") &&
                                                 Catch::Contains("--store " + d.string() + "/evaluations.sqlite"));
  // an 'evaluations' table of another layout (no 'program' column)
  const std::string other = (d / "other.sqlite").string();
  {
    Store s(other, false);
  }
  {
    // rebuild the table without 'program', as another tool might have
    sqlite3* db = nullptr;
    REQUIRE(sqlite3_open(other.c_str(), &db) == SQLITE_OK);
    REQUIRE(sqlite3_exec(db, "DROP TABLE evaluations; CREATE TABLE evaluations(key TEXT, value REAL);", nullptr, nullptr,
                         nullptr) == SQLITE_OK);
    sqlite3_close(db);
  }
  CHECK_THROWS_WITH(Store(other, false), Catch::Contains("has another layout") && Catch::Contains("no such column") &&
                                             Catch::Contains("move the file away"));
  CHECK_THROWS_WITH(Store(other, true), Catch::Contains("has another layout"));
  // a text file
  const std::string text = (d / "notes.sqlite").string();
  { std::ofstream(text) << "these are not records, just a text file long enough to have a header page\n"; }
  CHECK_THROWS_WITH(Store(text, true), Catch::Contains("is not an SQLite database"));
}
