// SPDX-License-Identifier: MIT
// The CalculiX .dat parser on real ccx 2.20 output (tests/solver/fixtures/README.md).
#include <catch2/catch.hpp>
#include <cmath>

#include "platform/eval/ccx_dat.hpp"

using namespace smi::eval;

namespace {
const std::string kDir = std::string(SMI_SOURCE_DIR) + "/tests/solver/fixtures/";
}

TEST_CASE("the eigenvalue table of a clamped plate's *FREQUENCY step") {
  const std::string f = kDir + "ccx_clamped.dat";
  const CcxDat r = parse_ccx_dat(read_text_file(f), f);
  REQUIRE(r.eigen.size() == 6);
  CHECK(r.blocks.empty());
  CHECK(r.eigen[0].mode == 1);
  CHECK(r.eigen[0].eigenvalue == 0.1554390E+06);
  CHECK(r.eigen[0].cycles == 0.6274803E+02);  // the spec's 62.75 Hz at h = 10 mm
  CHECK(r.eigen[2].cycles == 0.4895913E+03);
  CHECK(r.eigen[5].mode == 6);
  CHECK(r.eigen[5].radians == 0.9505637E+04);
  for (const auto& e : r.eigen) {
    // One number three ways: lambda = omega^2 and f = omega / 2 pi (7 digits printed).
    CHECK(e.radians * e.radians == Approx(e.eigenvalue).epsilon(1e-6));
    CHECK(e.radians / (2 * M_PI) == Approx(e.cycles).epsilon(1e-6));
    CHECK(e.imaginary == 0);
  }
}

TEST_CASE("displacement and stress blocks, each with its mode, set and columns") {
  const std::string f = kDir + "ccx_joint_sensor.dat";
  const CcxDat r = parse_ccx_dat(read_text_file(f), f);
  REQUIRE(r.eigen.size() == 6);
  CHECK(r.eigen[0].cycles == 0.5632674E+02);
  REQUIRE(r.blocks.size() == 12);  // U and S for each of 6 modes
  const CcxBlock& u = r.blocks[0];
  CHECK(u.name == "displacements");
  CHECK(u.set == "TIP");
  CHECK(u.time == 1.0);
  CHECK(u.mode == 1);
  CHECK(u.columns == std::vector<std::string>{"node", "vx", "vy", "vz"});
  REQUIRE(u.rows.rows() == 2);
  CHECK(u.rows(0, 0) == 43);
  CHECK(u.rows(1, 3) == -2.088246E+02);
  const CcxBlock& s = r.blocks[1];
  CHECK(s.name == "stresses");
  CHECK(s.set == "ROOT");
  CHECK(s.columns == std::vector<std::string>{"elem", "integ_pnt", "sxx", "syy", "szz", "sxy", "sxz", "syz"});
  REQUIRE(s.rows.rows() == 8);
  CHECK(s.rows(3, 1) == 4);
  CHECK(s.rows(3, 2) == -6.913694E+02);  // the "_shell_..." label after the numbers is dropped
  CHECK(r.blocks[11].mode == 6);
  CHECK(r.blocks[11].name == "stresses");
}

TEST_CASE("a file without results and a malformed row are errors naming the file and line") {
  CHECK_THROWS_WITH(parse_ccx_dat("\n *INFO: nothing\n", "job.dat"),
                    Catch::Contains("'job.dat' has no E I G E N V A L U E   O U T P U T table"));
  const std::string bad =
      "     E I G E N V A L U E   O U T P U T\n\n MODE NO    EIGENVALUE\n\n"
      "      1   0.1554390E+06   0.3942575E+03   0.6274803E+02   0.0000000E+00\n"
      "      2   0.6069984E+07   0.2463734E+04\n";
  CHECK_THROWS_WITH(parse_ccx_dat(bad, "job.dat"), Catch::Contains("'job.dat' line 6: eigenvalue row has 3 fields"));
  const std::string block = " displacements (vx,vy,vz) for set TIP and time  0.1000000E+01\n\n  43 1.0\n";
  CHECK_THROWS_WITH(parse_ccx_dat(block, "u.dat"), Catch::Contains("'u.dat' line 3: a row of 'displacements' has 2 numbers"));
}
