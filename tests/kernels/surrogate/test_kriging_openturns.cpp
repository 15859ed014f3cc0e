// SPDX-License-Identifier: MIT
// At fixed hyperparameters our predictor and MSE equal OpenTURNS' KrigingAlgorithm
// (tests/reference/kriging_openturns.py, spec §4 mapping theta = 1/(2 s^2), amplitude 1 on
// DACE-normalised data), for constant, linear and quadratic trends.
#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <sstream>

#include "kernels/surrogate/kriging.hpp"

using namespace smi::surrogate::kriging;

TEST_CASE("predictions and MSE equal OpenTURNS at fixed theta") {
  std::ifstream f(SMI_TEST_REFERENCE_DIR "/kriging_openturns.csv");
  REQUIRE(f.good());
  std::vector<std::vector<double>> design;
  std::map<std::string, std::vector<std::vector<double>>> cases;
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string tag, c;
    std::getline(ss, tag, ',');
    std::vector<double> v;
    while (std::getline(ss, c, ',')) v.push_back(std::stod(c));
    (tag == "design" ? design : cases[tag]).push_back(v);
  }
  REQUIRE(design.size() == 25);
  REQUIRE(cases.size() == 3);
  Eigen::MatrixXd S(25, 3);
  Eigen::VectorXd Y(25);
  for (int i = 0; i < 25; ++i) {
    S.row(i) << design[i][0], design[i][1], design[i][2];
    Y[i] = design[i][3];
  }
  for (auto& [name, rows] : cases) {
    FitOptions o;
    o.trend = parse_trend(name);
    o.theta = Eigen::Vector3d(rows[0][0], rows[0][1], rows[0][2]);
    const Model m = fit(S, Y, o);
    Eigen::MatrixXd T(rows.size(), 3);
    for (std::size_t i = 0; i < rows.size(); ++i) T.row(i) << rows[i][3], rows[i][4], rows[i][5];
    const Prediction p = predict(m, T);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      INFO(name << " point " << i);
      CHECK(std::abs((p.mean[i] - m.mY) / m.sY - rows[i][6]) < 1e-9);
      CHECK(std::abs(p.mse[i] / m.process_variance() - rows[i][7]) < 1e-9 * (1 + rows[i][7]));
    }
  }
}
