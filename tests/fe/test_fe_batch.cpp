// SPDX-License-Identifier: MIT
// smi-column-fe --batch POINTS.csv --base DECK -o OUT.csv: many points in one process. Checked
// against the spec's §11 reference values and against the single-deck solution of each point.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "batch.hpp"
#include "deck.hpp"
#include "fe_test_util.hpp"

namespace fs = std::filesystem;

namespace {

struct Run {
  int code;
  std::string out, err;
};

std::string slurp(const std::string& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

Run run(const std::string& args) {
  const std::string out = FE_WORK_DIR "/batch.stdout", err = FE_WORK_DIR "/batch.stderr";
  const int status = std::system((std::string("'") + FE_PROGRAM + "' " + args + " >" + out + " 2>" + err).c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

void write(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
}

/// OUT.csv rows as numbers (point, mode1..mode4).
std::vector<std::array<double, 5>> read_out(const std::string& path) {
  std::istringstream is(slurp(path));
  std::string line;
  std::getline(is, line);
  REQUIRE(line == "point,mode1_hz,mode2_hz,mode3_hz,mode4_hz");
  std::vector<std::array<double, 5>> rows;
  while (std::getline(is, line)) {
    std::array<double, 5> r{};
    std::istringstream ls(line);
    std::string cell;
    for (double& x : r) {
      std::getline(ls, cell, ',');
      x = std::stod(cell);
    }
    rows.push_back(r);
  }
  return rows;
}

const std::string kPoints =
    "column_frame_E,ecu_bracket_thickness,wheel_cover_rho,wheel_cover_thickness\n"
    "205000,3.2,1e-9,5.5\n"            // nominal
    "307500,4.8,0.5e-9,2.75\n"         // the §8 corner: lateral comes first
    "181234.5,2.91,1.31e-9,6.2\n";     // an arbitrary point

}  // namespace

TEST_CASE("batch mode reproduces the §11 values and the single-deck solutions", "[fe][program][batch]") {
  const std::string pts = FE_WORK_DIR "/pts.csv", out = FE_WORK_DIR "/pts_out.csv";
  write(pts, kPoints);
  fs::remove(out);
  const Run r = run("--batch " + pts + " --base " FE_DECK_DIR "/nominal_rigid.deck -o " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto rows = read_out(out);
  REQUIRE(rows.size() == 3);
  // §11: nominal rigid 29.6372, 33.5958, 38.2634, 80.2333 (6 digits); corner 44.12, 41.67, 50.52, 111.0.
  const double nominal[4] = {29.6372, 33.5958, 38.2634, 80.2333};
  for (int m = 0; m < 4; ++m) CHECK(std::abs(rows[0][m + 1] - nominal[m]) <= fe_test::half_unit(nominal[m], 6));
  const double corner[4] = {44.12, 41.67, 50.52, 111.0};
  for (int m = 0; m < 4; ++m) CHECK(std::abs(rows[1][m + 1] - corner[m]) <= fe_test::half_unit(corner[m], 4));
  // The third point equals a single run of the same inputs (printed with 10 digits).
  cfe::Inputs in = cfe::nominal_inputs(cfe::Airbag::rigid);
  in.set("column_frame_E", 181234.5);
  in.set("ecu_bracket_thickness", 2.91);
  in.set("wheel_cover_rho", 1.31e-9);
  in.set("wheel_cover_thickness", 6.2);
  const auto hz = fe_test::paper_hz(in);
  for (int m = 0; m < 4; ++m) CHECK(std::abs(rows[2][m + 1] - hz[m]) <= 1e-9 * hz[m]);
  CHECK(rows[2][0] == 3);
}

TEST_CASE("batch mode on a spring base takes airbag_stiffness per point; threads change nothing", "[fe][program][batch]") {
  const std::string pts = FE_WORK_DIR "/pts_k.csv", out1 = FE_WORK_DIR "/pts_k1.csv", out2 = FE_WORK_DIR "/pts_k2.csv";
  write(pts, "airbag_stiffness,column_frame_E\n1000,205000\n600,205000\n1400,230000\n1000,205000\n");
  const std::string base = " --base " FE_DECK_DIR "/nominal_spring.deck -o ";
  REQUIRE(run("--batch " + pts + base + out1).code == 0);
  REQUIRE(run("--batch " + pts + base + out2 + " --threads 2").code == 0);
  CHECK(slurp(out1) == slurp(out2));
  const auto rows = read_out(out1);
  REQUIRE(rows.size() == 4);
  // §11 nominal spring mode 4 = 72.6656; a softer airbag lowers the wheel-pitch mode.
  CHECK(std::abs(rows[0][4] - 72.6656) <= fe_test::half_unit(72.6656, 6));
  CHECK(rows[1][4] < rows[0][4] - 1.0);
  CHECK(rows[3] == std::array<double, 5>{4, rows[0][1], rows[0][2], rows[0][3], rows[0][4]});
}

TEST_CASE("batch mode refuses bad points and usage, naming the culprit; no output left", "[fe][program][batch]") {
  const std::string pts = FE_WORK_DIR "/bad_pts.csv", out = FE_WORK_DIR "/bad_out.csv";
  const std::string tail = " --base " FE_DECK_DIR "/nominal_rigid.deck -o " + out;
  fs::remove(out);
  write(pts, "column_frame_E,ecu_braket_thickness\n205000,3.2\n");
  Run r = run("--batch " + pts + tail);
  CHECK(r.code == 1);
  CHECK(r.err.find("header names 'ecu_braket_thickness', which is not an input") != std::string::npos);
  write(pts, "column_frame_E,column_frame_nu\n205000,0.29\n205000,0.51\n");
  r = run("--batch " + pts + tail);
  CHECK(r.code == 1);
  CHECK(r.err.find("row 2, column 'column_frame_nu', value '0.51': a Poisson's ratio must lie in (0, 0.5)") != std::string::npos);
  write(pts, "column_frame_E\n-3\n");
  r = run("--batch " + pts + tail);
  CHECK(r.err.find("row 1, column 'column_frame_E', value '-3': must be > 0") != std::string::npos);
  write(pts, "column_frame_E,hub_E\n205000\n");
  r = run("--batch " + pts + tail);
  CHECK(r.err.find("has 1 values but the header names 2 inputs") != std::string::npos);
  write(pts, "column_frame_E\n2e5x\n");
  r = run("--batch " + pts + tail);
  CHECK(r.err.find("row 1, column 'column_frame_E', value '2e5x': not a number") != std::string::npos);
  CHECK(!fs::exists(out));
  r = run("--batch " + pts + " -o " + out);
  CHECK(r.code == 2);
  CHECK(r.err.find("--batch needs --base DECK") != std::string::npos);
  r = run(std::string(FE_DECK_DIR) + "/nominal_rigid.deck --base x.deck -o " + out);
  CHECK(r.code == 2);
  CHECK(r.err.find("--base is only used with --batch") != std::string::npos);
  r = run("--batch " + pts + tail + " --threads 0");
  CHECK(r.code == 2);
  CHECK(r.err.find("--threads needs an integer from 1 to 64") != std::string::npos);
}
