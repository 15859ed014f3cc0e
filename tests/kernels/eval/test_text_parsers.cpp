// Regular-expression and CSV readers of solver output.
#include <catch2/catch.hpp>

#include "eval/text_parsers.hpp"

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
