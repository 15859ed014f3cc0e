// SPDX-License-Identifier: MIT
// The one CSV codec (core/csv.hpp) against RFC 4180's grammar: quoted fields holding the
// separator, quotes and line breaks; CRLF; a BOM; and the writer's quoting reading back.
#include <catch2/catch.hpp>

#include "platform/core/csv.hpp"
#include "platform/core/errors.hpp"

namespace csv = smi::csv;

TEST_CASE("csv reads RFC 4180 records") {
  // RFC 4180 section 2, rules 5-7: quoted fields with a comma, CRLF and a doubled quote.
  const auto recs = csv::read("\xEF\xBB\xBF" "a,\"b,c\",\"say \"\"hi\"\"\"\r\n\"two\r\nlines\",x,\r\n\r\n# not a comment\n",
                              "t.csv");
  REQUIRE(recs.size() == 3);
  CHECK(recs[0].fields == std::vector<std::string>{"a", "b,c", "say \"hi\""});
  CHECK(recs[1].fields == std::vector<std::string>{"two\r\nlines", "x", ""});
  CHECK(recs[1].line == 2);
  CHECK(recs[2].line == 5);
  csv::ReadOptions o;
  o.comment = '#';
  o.sep = ';';
  const auto c = csv::read("  # note\nx;y\n1;2\n", "t.csv", o);
  REQUIRE(c.size() == 2);
  CHECK(c[1].fields == std::vector<std::string>{"1", "2"});
  CHECK_THROWS_WITH(csv::read("a\n\"open\nstill", "t.csv"), "line 2 of t.csv: a quoted field never ends (missing '\"')");
}

TEST_CASE("csv writes cells that read back, numbers whole") {
  const std::vector<std::string> header = {"load, N", "tag"};
  const std::vector<std::vector<std::string>> cols = {{"1", "2"}, {"q\"r", "line\nbreak"}};
  const std::string text = csv::write(header, cols);
  CHECK(text == "\"load, N\",tag\n1,\"q\"\"r\"\n2,\"line\nbreak\"\n");
  const auto back = csv::read(text, "w.csv");
  REQUIRE(back.size() == 3);
  CHECK(back[0].fields == header);
  CHECK(back[2].fields[1] == "line\nbreak");
  double v = 0;
  CHECK(csv::parse_number(" 2.5e3\r", v));
  CHECK(v == 2500);
  CHECK_FALSE(csv::parse_number("2.5x", v));
  CHECK_FALSE(csv::parse_number("  ", v));
}

TEST_CASE("csv sniffs another separator and decimal commas") {
  CHECK(csv::sniff("a;b;c\n1;2;3\n", ',') == "the file uses ';' between fields: pass sep = ';' or save as CSV");
  CHECK(csv::sniff("a\tb\n1\t2\n", ',') == "the file uses a tab between fields: pass sep = '\\t' or save as CSV");
  CHECK(csv::sniff("\xEF\xBB\xBFspecimen;hz\r\n1;31,84\r\n", ',') ==
        "the file uses ';' between fields and ',' as the decimal mark: pass sep = ';', decimal = ',' or save as CSV "
        "with '.' decimals");
  CHECK(csv::sniff("a,b\n1;2,3\n", ',').empty());  // the header splits on ',': it is the separator
  CHECK(csv::sniff("a\n1\n", ',').empty());        // one column, nothing else shows
  CHECK(csv::decimal_comma("-0,5"));
  CHECK(csv::decimal_comma(" 31,84 "));
  CHECK_FALSE(csv::decimal_comma("1,2.5"));
  CHECK_FALSE(csv::decimal_comma("a,b"));
  CHECK_FALSE(csv::decimal_comma(",5"));
}
