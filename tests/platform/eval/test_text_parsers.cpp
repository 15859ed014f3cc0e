// SPDX-License-Identifier: MIT
// Regular-expression and CSV readers of solver output.
#include <catch2/catch.hpp>

#include "platform/eval/text_parsers.hpp"

using namespace smi::eval;

TEST_CASE("regex_number takes the first capture, regex_numbers every match") {
  const std::string log = "iter 1 residual 1.5e-3\niter 2 residual 2.5E-04\nMAX DISP = -0.125 mm\n";
  CHECK(regex_number(log, R"(MAX DISP = (\S+))", "log") == -0.125);
  const Eigen::VectorXd r = regex_numbers(log, R"(residual ([-+0-9.eE]+))", "log");
  REQUIRE(r.size() == 2);
  CHECK(r[0] == 1.5e-3);
  CHECK(r[1] == 2.5e-4);
  CHECK_THROWS_WITH(regex_number(log, "STRESS = (\\S+)", "out.log"), Catch::Contains("'out.log': no match"));
  CHECK_THROWS_WITH(regex_number("x = abc", R"(x = (\w+))", "o"), Catch::Contains("'abc', which is not a number"));
  CHECK_THROWS_WITH(regex_number(log, "(", "o"), Catch::Contains("bad regular expression"));
}

// std::regex recursed once per character: a 200 KB line in a solver's output overflowed the
// stack (a segfault pcall cannot catch). RE2 is linear and recursion-free.
TEST_CASE("regex parsers survive 1 MB lines and 1 MB tokens") {
  std::string line(1 << 20, 'a');  // one 1 MB token, then the value on the same line
  line += " MAX DISP = -0.125 mm\n";
  CHECK(regex_number(line, R"(MAX DISP = (\S+))", "big.log") == -0.125);
  CHECK(regex_number(line, R"((?:a|b)+ MAX DISP = ([-0-9.]+))", "big.log") == -0.125);
  // the 1 MB token itself captured: not a number, and the message stays readable
  CHECK_THROWS_WITH(regex_number(line, R"(^(\S+))", "big.log"),
                    Catch::Contains("which is not a number") && Catch::Contains("..."));
  // a 1 MB line of numbers: every one found, in order
  std::string nums;
  for (int i = 0; i < 100000; ++i) nums += "v=" + std::to_string(i) + " ";
  const Eigen::VectorXd v = regex_numbers(nums, R"(v=(\d+))", "nums.log");
  REQUIRE(v.size() == 100000);
  CHECK(v[99999] == 99999.0);
  // a pattern that backtracks exponentially in a backtracking engine: linear here
  CHECK_THROWS_WITH(regex_number(std::string(1 << 20, 'a'), "(a*)*b", "o"), Catch::Contains("no match"));
}

TEST_CASE("a pattern RE2 cannot run is refused naming it and the reason") {
  CHECK_THROWS_WITH(regex_number("x = 1 1", R"(x = (\d) \1)", "out.log"),
                    Catch::Contains("bad regular expression /x = (\\d) \\1/ for 'out.log'") &&
                        Catch::Contains("no backreferences"));
  CHECK_THROWS_WITH(regex_number("x = 1", R"(x(?= )= (\d))", "out.log"), Catch::Contains("lookaround"));
}

TEST_CASE("csv_column reads a named column and names bad cells") {
  const std::string csv = "# results\nmode, freq ,mass\n1,29.6,1\n\n2, 33.6 ,1\n";
  const Eigen::VectorXd f = csv_column(csv, "freq", "r.csv");
  REQUIRE(f.size() == 2);
  CHECK(f[0] == 29.6);
  CHECK(f[1] == 33.6);
  CHECK_THROWS_WITH(csv_column(csv, "cycles", "r.csv"), Catch::Contains("no column 'cycles'") && Catch::Contains("mode, freq, mass"));
  CHECK_THROWS_WITH(csv_column("a,b\n1,x\n", "b", "r.csv"), Catch::Contains("line 2 column 'b': 'x' is not a number"));
  CHECK_THROWS_WITH(csv_column("a,b\n1\n", "b", "r.csv"), Catch::Contains("1 fields, the header has 2"));
}

TEST_CASE("csv_column reads RFC 4180 quoting as smi.csv.read does (one codec)") {
  // A quoted header holding the separator, CRLF line ends, a BOM and a quoted number cell: the
  // old splitter cut "load, N" at the comma and never found the column.
  const std::string csv = "\xEF\xBB\xBF\"load, N\",freq\r\n1200,29.6\r\n\"1500\",\"33.6\"\r\n";
  CHECK(csv_column(csv, "load, N", "r.csv") == Eigen::Vector2d(1200, 1500));
  CHECK(csv_column(csv, "freq", "r.csv") == Eigen::Vector2d(29.6, 33.6));
  CHECK_THROWS_WITH(csv_column("a,b\n1,\"2\n", "b", "r.csv"), Catch::Contains("line 2 of r.csv: a quoted field never ends"));
}
