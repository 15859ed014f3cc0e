// SPDX-License-Identifier: MIT
// Tails against exact values: mpmath at 60 digits from the closed forms
// (tests/reference/tails_exact.py -> tails_exact.csv), down to 1e-300 where representable:
// triangular with its mode at a bound (cdf, logcdf, sf, quantile, isf), logcdf far in the lower
// tail of weibull, truncnormal and triangular, and the Gaussian KDE's sf, logpdf, logcdf,
// quantile and isf far from its data. Before, these lost up to 1e-4 relative
// (triangular), returned −inf (logcdf; the KDE's logpdf 10 h and logcdf 5 h away), 0 (the KDE's
// sf 8 h away) or inf (the KDE's isf(1e-20)).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "kernels/stats/families.hpp"
#include "kernels/stats/kde.hpp"

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::map<std::string, std::shared_ptr<smi::stats::Distribution>> cases() {
  using namespace smi::stats;
  return {
      {"tri_lo", std::make_shared<Triangular>(0.0, 0.0, 3.0)},
      {"tri_hi", std::make_shared<Triangular>(0.0, 3.0, 3.0)},
      {"tri", std::make_shared<Triangular>(0.0, 1.0, 3.0)},
      {"weibull", std::make_shared<Weibull>(1.7, 2.0, 0.5)},
      {"weibull_k17", std::make_shared<Weibull>(1.7, 2.0)},
      {"weibull_k06", std::make_shared<Weibull>(0.6, 1.0)},
      {"truncnormal_lo", std::make_shared<TruncNormal>(0.0, 1.0, -kInf, -5.0)},
      {"truncnormal_20", std::make_shared<TruncNormal>(0.0, 1.0, -20.0, 5.0)},
      {"kde", std::make_shared<Kde>(Eigen::Vector3d(0.0, 1.0, 2.5), 0.5)},
  };
}

double eval(const smi::stats::Distribution& d, const std::string& kind, double a) {
  if (kind == "cdf") return d.cdf(a);
  if (kind == "sf") return d.sf(a);
  if (kind == "logcdf") return d.logcdf(a);
  if (kind == "logpdf") return d.logpdf(a);
  if (kind == "quantile") return d.quantile(a);
  if (kind == "isf") return d.isf(a);
  FAIL("unknown kind " << kind);
  return 0.0;
}

}  // namespace

TEST_CASE("tails: every value within 1e-12 relative of mpmath's exact one") {
  std::ifstream f(std::string(SMI_TEST_REFERENCE_DIR) + "/tails_exact.csv");
  REQUIRE(f.good());
  const auto dists = cases();
  std::string line;
  std::getline(f, line);  // header
  int rows = 0;
  while (std::getline(f, line)) {
    std::stringstream ss(line);
    std::string c, kind, arg, value;
    std::getline(ss, c, ',');
    std::getline(ss, kind, ',');
    std::getline(ss, arg, ',');
    std::getline(ss, value, ',');
    const double a = std::stod(arg), want = std::stod(value);
    const double got = eval(*dists.at(c), kind, a);
    INFO(c << " " << kind << "(" << arg << ") = " << got << ", exact " << value);
    REQUIRE(std::isfinite(got));
    CHECK(std::abs(got - want) <= 1e-12 * std::abs(want) + 1e-300);
    ++rows;
  }
  CHECK(rows > 150);
}
