// SPDX-License-Identifier: MIT
// The real smi-column-fe executable, run as outside checks run it: `smi-column-fe DECK -o RESULTS`.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "fe_test_util.hpp"

namespace fs = std::filesystem;

namespace {

struct Run {
  int code;
  std::string out, err;
};

Run run(const std::string& args) {
  const std::string out = FE_WORK_DIR "/prog.stdout", err = FE_WORK_DIR "/prog.stderr";
  const int status = std::system((std::string("'") + FE_PROGRAM + "' " + args + " >" + out + " 2>" + err).c_str());
  auto slurp = [](const std::string& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  };
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

// The file prints 7 significant digits, so its rounding adds to the spec's 6-digit rounding.
double file_tol(double ref) { return fe_test::half_unit(ref, 6) + fe_test::half_unit(ref, 7); }

}  // namespace

TEST_CASE("smi-column-fe solves the spec's example deck (model B) to the §11 values", "[fe][program]") {
  const std::string res = FE_WORK_DIR "/nominal_spring.f06";
  fs::remove(res);
  const Run r = run(std::string(FE_DECK_DIR) + "/nominal_spring.deck -o " + res);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  std::ifstream f(res);
  const cfe::Results out = cfe::read_results(f, res);
  CHECK(out.airbag == "SPRING");
  CHECK(out.dof == 288);
  const double ref[10] = {29.6953, 33.3360, 38.4813, 72.6656, 89.1659, 90.7440, 110.996, 125.564, 128.898, 145.043};
  REQUIRE(out.modes.size() == 10);
  for (int k = 0; k < 10; ++k) CHECK(std::abs(out.modes[k].cycles - ref[k]) <= file_tol(ref[k]));
  CHECK(out.paper_mode == std::array<int, 4>{1, 2, 3, 4});
  CHECK(std::abs(out.paper_hz[3] - 72.6656) <= file_tol(72.6656));
  CHECK(!fs::exists(res + ".part"));
}

TEST_CASE("smi-column-fe refuses a bad deck: non-zero exit, message on stderr, no results file", "[fe][program]") {
  const std::string deck = FE_WORK_DIR "/bad.deck", res = FE_WORK_DIR "/bad.f06";
  fs::remove(res);
  {
    std::ofstream f(deck);
    f << "# bad deck\nairbag_model = rigid\ncolumn_frame_E = 2.05e5x\n";
  }
  const Run r = run(deck + " -o " + res);
  CHECK(r.code == 1);
  CHECK(r.err.find("bad.deck:3: key 'column_frame_E' value '2.05e5x': not a number") != std::string::npos);
  CHECK(!fs::exists(res));
}

TEST_CASE("smi-column-fe usage, --help and --version", "[fe][program]") {
  Run r = run("--version");
  CHECK(r.code == 0);
  CHECK(r.out.rfind("smi-column-fe ", 0) == 0);
  r = run("--help");
  CHECK(r.code == 0);
  CHECK(r.out.find("smi-column-fe DECK -o RESULTS") != std::string::npos);
  r = run(std::string(FE_DECK_DIR) + "/nominal_rigid.deck");
  CHECK(r.code == 2);
  CHECK(r.err.find("-o RESULTS") != std::string::npos);
  r = run(std::string(FE_DECK_DIR) + "/nominal_rigid.deck -o " FE_WORK_DIR "/x.f06 --frobnicate");
  CHECK(r.code == 2);
  CHECK(r.err.find("unknown option '--frobnicate'") != std::string::npos);
}
