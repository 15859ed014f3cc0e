// SPDX-License-Identifier: MIT
// The input deck of spec §9: every error names file, line, key and value; the writer round-trips.
#include <catch2/catch.hpp>

#include <fstream>
#include <regex>
#include <sstream>

#include "deck.hpp"

using cfe::Airbag;

namespace {

std::string nominal_text(Airbag a) { return cfe::write_deck(cfe::nominal_inputs(a)); }

// Replace the line starting with `key =` by `line`; returns the 1-based line number.
int replace_line(std::string& text, const std::string& key, const std::string& line) {
  std::istringstream is(text);
  std::ostringstream os;
  std::string l;
  int n = 0, at = -1;
  while (std::getline(is, l)) {
    ++n;
    if (l.rfind(key + " =", 0) == 0) {
      l = line;
      at = n;
    }
    os << l << "\n";
  }
  text = os.str();
  return at;
}

void expect_error(const std::string& text, const std::string& fragment) {
  INFO("expected an error containing: " << fragment);
  CHECK_THROWS_WITH(cfe::parse_deck(text, "case.deck"), Catch::Contains(fragment));
}

}  // namespace

TEST_CASE("the spec's example deck parses to the nominal inputs", "[fe][deck]") {
  std::ifstream f(FE_DECK_DIR "/nominal_spring.deck");
  std::stringstream ss;
  ss << f.rdbuf();
  const cfe::Inputs in = cfe::parse_deck(ss.str(), "nominal_spring.deck");
  const cfe::Inputs nom = cfe::nominal_inputs(Airbag::spring);
  CHECK(in.airbag == Airbag::spring);
  CHECK(in.refinement == 1);
  CHECK(in.values == nom.values);
}

TEST_CASE("write_deck / parse_deck round-trip bit for bit, comments and blanks ignored", "[fe][deck]") {
  cfe::Inputs in = cfe::nominal_inputs(Airbag::spring, 3);
  in.set("column_frame_E", 1.0 / 3.0 * 6e5);
  in.set("wheel_cover_rho", 1.2345678901234567e-9);
  const std::string text = cfe::write_deck(in) + "\n   # trailing comment\n\n";
  const cfe::Inputs back = cfe::parse_deck(text, "rt.deck");
  CHECK(back.values == in.values);
  CHECK(back.refinement == 3);
  std::string spaced = cfe::write_deck(cfe::nominal_inputs(Airbag::rigid));
  replace_line(spaced, "hub_E", "   hub_E   =   200000   # steel hub");
  CHECK(cfe::parse_deck(spaced, "s.deck")("hub_E") == 200000.0);
}

TEST_CASE("bad values name file, line, key and value", "[fe][deck]") {
  const struct {
    const char* key;
    const char* value;
    const char* what;
  } cases[] = {
      {"hub_E", "abc", "not a number"},
      {"hub_E", "12x", "not a number"},
      {"hub_E", "", "not a number"},
      {"hub_E", "inf", "not finite"},
      {"hub_E", "nan", "not finite"},
      {"tilt_lock_k", "0", "must be > 0"},
      {"tilt_lock_k", "-200", "must be > 0"},
      {"hub_nu", "0", "a Poisson's ratio must lie in (0, 0.5)"},
      {"hub_nu", "0.5", "a Poisson's ratio must lie in (0, 0.5)"},
      {"wheel_cover_nu", "0.7", "a Poisson's ratio must lie in (0, 0.5)"},
      {"airbag_model", "soft", "must be 'rigid' or 'spring'"},
      {"airbag_stiffness", "-1", "must be > 0"},
  };
  for (const auto& c : cases) {
    std::string text = nominal_text(Airbag::spring);
    const int line = replace_line(text, c.key, std::string(c.key) + " = " + c.value);
    REQUIRE(line > 0);
    expect_error(text, "case.deck:" + std::to_string(line) + ": key '" + c.key + "' value '" + c.value + "': " + c.what);
  }
}

TEST_CASE("unknown, duplicate and missing keys", "[fe][deck]") {
  std::string text = nominal_text(Airbag::rigid);
  int line = replace_line(text, "tilt_lock_k", "tilt_lok_k = 200");
  expect_error(text, "case.deck:" + std::to_string(line) + ": key 'tilt_lok_k' value '200': unknown key; did you mean 'tilt_lock_k'?");

  text = nominal_text(Airbag::rigid) + "hub_E = 3\n";
  expect_error(text, "key 'hub_E' value '3': duplicate key (first given on line");

  text = nominal_text(Airbag::rigid);
  replace_line(text, "bush3_kv", "# bush3_kv removed");
  expect_error(text, "case.deck: missing required key(s): bush3_kv");

  text = nominal_text(Airbag::rigid);
  replace_line(text, "airbag_model", "");
  expect_error(text, "missing required key(s): airbag_model");

  // airbag_stiffness is required for spring only.
  text = nominal_text(Airbag::spring);
  replace_line(text, "airbag_stiffness", "");
  expect_error(text, "missing required key(s): airbag_stiffness");
  text = nominal_text(Airbag::rigid);
  CHECK(text.find("airbag_stiffness") == std::string::npos);
  CHECK_NOTHROW(cfe::parse_deck(text, "ok.deck"));

  text = nominal_text(Airbag::rigid) + "no equals sign here\n";
  expect_error(text, "expected 'key = value'");
}

TEST_CASE("mesh_refinement is an integer 1..8", "[fe][deck]") {
  for (const char* bad : {"0", "9", "1.5", "two"}) {
    std::string text = nominal_text(Airbag::rigid) + "mesh_refinement = " + bad + "\n";
    expect_error(text, std::string("key 'mesh_refinement' value '") + bad + "': must be an integer from 1 to 8");
  }
  CHECK(cfe::parse_deck(nominal_text(Airbag::rigid) + "mesh_refinement = 8\n", "r.deck").refinement == 8);
}

TEST_CASE("an unreadable deck names the path", "[fe][deck]") {
  CHECK_THROWS_WITH(cfe::read_deck("/nonexistent/dir/x.deck"), Catch::Contains("/nonexistent/dir/x.deck: cannot open"));
}
