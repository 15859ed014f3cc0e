// SPDX-License-Identifier: MIT
// The .f06-like results file of spec §10: exact C formats and a read-back round trip.
#include <catch2/catch.hpp>

#include <sstream>
#include <vector>

#include <cmath>

#include "fe_test_util.hpp"

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream is(text);
  for (std::string l; std::getline(is, l);) out.push_back(l);
  return out;
}

}  // namespace

TEST_CASE("results file reproduces the spec §10 example layout", "[fe][results]") {
  std::ostringstream os;
  cfe::write_results(os, cfe::run_model(cfe::nominal_inputs(cfe::Airbag::rigid)));
  const auto L = lines_of(os.str());
  REQUIRE(L.size() == 34);
  // Lines copied from the spec's example (those not subject to last-digit rounding).
  CHECK(L[0] == "1    STEERING COLUMN ANALOG");
  CHECK(L[1] == "     AIRBAG MODEL = RIGID    DOF = 282");
  CHECK(L[2] == "0");
  CHECK(L[3] == "                                              R E A L   E I G E N V A L U E S");
  CHECK(L[4] == "   MODE    EXTRACTION      EIGENVALUE            RADIANS             CYCLES            GENERALIZED         GENERALIZED");
  CHECK(L[5] == "    NO.       ORDER                                                                       MASS              STIFFNESS");
  CHECK(L[7] == "        2         2        4.455839E+04        2.110886E+02        3.359579E+01        1.000000E+00        4.455839E+04");
  CHECK(L[9] == "        4         4        2.541376E+05        5.041206E+02        8.023328E+01        1.000000E+00        2.541376E+05");
  CHECK(L[15] == "       10        10        2.594403E+06        1.610715E+03        2.563533E+02        1.000000E+00        2.594403E+06");
  CHECK(L[16] == "0");
  CHECK(L[17] == "                                              M O D E   L A B E L S");
  CHECK(L[18] == "   MODE          CYCLES  DIRECTION      PAPER   P(TA)  P(TL)  P(TV)  P(RA)  P(RL)  P(RV)");
  CHECK(L[19] == "      1    2.963724E+01  VERTICAL          1  0.000  0.000  0.802  0.000  0.258  0.000");
  CHECK(L[22] == "      4    8.023328E+01  WHEEL_PITCH       4  0.024  0.000  0.022  0.000  0.602  0.000");
  CHECK(L[23] == "      5    9.730354E+01  WHEEL_YAW         -  0.000  0.042  0.000  0.003  0.000  0.538");
  CHECK(L[28] == "     10    2.563533E+02  LATERAL           -  0.000  0.060  0.000  0.001  0.000  0.055");
  CHECK(L[29] == "0");
  CHECK(L[30] == "     PAPER MODE 1  VERTICAL      MODE   1  2.963724E+01 HZ");
  CHECK(L[33] == "     PAPER MODE 4  WHEEL_PITCH   MODE   4  8.023328E+01 HZ");
}

TEST_CASE("results file reads back to what was written (to the printed digits)", "[fe][results]") {
  const cfe::Results r = cfe::run_model(fe_test::corner(cfe::Airbag::spring));
  std::ostringstream os;
  cfe::write_results(os, r);
  std::istringstream is(os.str());
  const cfe::Results back = cfe::read_results(is, "corner.f06");
  CHECK(back.airbag == "SPRING");
  CHECK(back.dof == 288);
  REQUIRE(back.modes.size() == r.modes.size());
  for (std::size_t k = 0; k < r.modes.size(); ++k) {
    CHECK(back.modes[k].cycles == Approx(r.modes[k].cycles).epsilon(1e-6));
    CHECK(back.modes[k].eigenvalue == Approx(r.modes[k].eigenvalue).epsilon(1e-6));
    CHECK(back.modes[k].direction == r.modes[k].direction);
    CHECK(back.modes[k].paper == r.modes[k].paper);
    for (int j = 0; j < 6; ++j) CHECK(back.modes[k].p[j] == Approx(r.modes[k].p[j]).margin(5e-4));
  }
  for (int m = 0; m < 4; ++m) {
    CHECK(back.paper_mode[m] == r.paper_mode[m]);
    CHECK(back.paper_hz[m] == Approx(r.paper_hz[m]).epsilon(1e-6));
  }
}

TEST_CASE("an absent label is written as NOT FOUND and read back as such", "[fe][results]") {
  cfe::Results r = cfe::run_model(cfe::nominal_inputs(cfe::Airbag::rigid));
  r.paper_mode[2] = 0;
  r.paper_hz[2] = std::nan("");
  r.modes[2].paper = 0;
  std::ostringstream os;
  cfe::write_results(os, r);
  CHECK(os.str().find("     PAPER MODE 3  TORSION       NOT FOUND\n") != std::string::npos);
  std::istringstream is(os.str());
  const cfe::Results back = cfe::read_results(is, "x.f06");
  CHECK(back.paper_mode[2] == 0);
  CHECK(std::isnan(back.paper_hz[2]));
}

TEST_CASE("a file that is not a results file is refused with its name", "[fe][results]") {
  std::istringstream is("hello\nworld\n");
  CHECK_THROWS_WITH(cfe::read_results(is, "junk.txt"), Catch::Contains("junk.txt"));
}
