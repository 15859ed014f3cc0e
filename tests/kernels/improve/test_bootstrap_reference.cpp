// SPDX-License-Identifier: MIT
// The bootstrap's percentile interval and the Monte Carlo error it reports, against SciPy's
// scipy.stats.bootstrap (tests/reference/bootstrap_scipy.py -> bootstrap_scipy.json) on the mean
// of 20 skewed data, whose calibration θ̂ = argmin Σ(x_i − θ)² is the mean exactly:
//   * with many replicates the interval is SciPy's 200000-resample one;
//   * the endpoint's Monte Carlo error the kernel reports from ONE bootstrap of 50 (or 400)
//     replicates, averaged over many seeds, is the spread SciPy's endpoints show over 400
//     independent bootstraps of that size, and so is the kernel's own spread over seeds;
//   * the replicates run side by side give the same numbers as one after another.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "kernels/improve/bootstrap.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/json.hpp"

using namespace smi::improve;

namespace {

smi::json::Value reference() {
  std::ifstream f(std::string(SMI_TEST_REFERENCE_DIR) + "/bootstrap_scipy.json");
  REQUIRE(f.good());
  std::stringstream s;
  s << f.rdbuf();
  return smi::json::read(s.str(), "bootstrap_scipy.json");
}

double at(const smi::json::Value& v, const char* a, const char* b) { return v.find(a)->find(b)->number(); }

Eigen::VectorXd data_of(const smi::json::Value& ref) {
  const auto& a = ref.find("data")->array();
  Eigen::VectorXd x(static_cast<Eigen::Index>(a.size()));
  for (std::size_t i = 0; i < a.size(); ++i) x[static_cast<Eigen::Index>(i)] = a[i].number();
  return x;
}

BootstrapResult mean_bootstrap(const Eigen::VectorXd& x, int replicates, std::uint64_t seed, int threads = 1) {
  std::vector<Parameter> p{{"m", 0.0, 5.0, 1.0}};
  ObjectiveFactory make = [](const std::vector<Eigen::VectorXd>& d) -> Objective {
    const Eigen::VectorXd y = d[0];
    return [y](const Eigen::VectorXd& t) { return Evaluation{(y.array() - t[0]).square().mean(), {}}; };
  };
  BootstrapOptions o;
  o.replicates = replicates;
  o.seed = seed;
  o.threads = threads;
  o.warm_start = true;  // a convex objective: one start finds the replicate's mean
  o.optimizer.xtol_rel = 1e-12;
  o.xtol_rel = 1e-12;  // the replicates' own tolerance too (its default, 1e-4, suits a study's spread)
  o.optimizer.ftol_abs = 1e-14;
  return bootstrap_calibration(p, Eigen::VectorXd::Constant(1, x.mean()), {x}, make, o);
}

}  // namespace

TEST_CASE("the percentile interval of a mean is SciPy's") {
  const smi::json::Value ref = reference();
  const Eigen::VectorXd x = data_of(ref);
  const BootstrapResult r = mean_bootstrap(x, 20000, 3);
  CHECK(std::abs(r.thetas.col(0).mean() - x.mean()) < 0.002);
  // SciPy's 200000-resample interval; the kernel's 20000 replicates leave about 0.002 of Monte Carlo error
  CHECK(r.lower[0] == Approx(at(ref, "reference", "lower")).margin(4 * r.lower_mc_error[0] + 1e-4));
  CHECK(r.upper[0] == Approx(at(ref, "reference", "upper")).margin(4 * r.upper_mc_error[0] + 1e-4));
  CHECK(r.lower_mc_error[0] < 0.004);
  CHECK(r.warnings.empty());
  // the normal interval: the estimate ± Φ⁻¹(0.975) sd, Φ⁻¹(0.975) = 1.959963984540054 (closed form)
  CHECK(r.normal_lower[0] == Approx(x.mean() - 1.959963984540054 * r.stddev[0]).epsilon(1e-12));
  CHECK(r.normal_upper[0] == Approx(x.mean() + 1.959963984540054 * r.stddev[0]).epsilon(1e-12));
  // the bootstrap sd of a mean is the plug-in standard error sd·sqrt((n−1)/n)/sqrt(n) to its MC error
  const double n = static_cast<double>(x.size());
  const double se = std::sqrt((x.array() - x.mean()).square().sum() / n) / std::sqrt(n);
  CHECK(r.stddev[0] == Approx(se).epsilon(0.02));
}

TEST_CASE("the normal interval stays inside the parameter's bounds") {
  const Eigen::VectorXd x = (Eigen::VectorXd(6) << 0.01, 0.02, 0.05, 0.1, 1.9, 2.8).finished();  // mean 0.813, bounds [0, 5]
  const BootstrapResult r = mean_bootstrap(x, 400, 5);
  REQUIRE(x.mean() - 1.96 * r.stddev[0] < 0.0);  // the unclipped lower end would leave [0, 5]
  CHECK(r.normal_lower[0] == 0.0);
  CHECK(r.normal_upper[0] == Approx(x.mean() + 1.959963984540054 * r.stddev[0]).epsilon(1e-12));
}

TEST_CASE("the endpoints' Monte Carlo error is the spread SciPy's endpoints have") {
  const smi::json::Value ref = reference();
  const Eigen::VectorXd x = data_of(ref);
  for (const int b : {50, 400}) {
    const std::string key = "spread_" + std::to_string(b);
    const int runs = 160;
    double said_lo = 0, said_hi = 0, s_lo = 0, ss_lo = 0, s_hi = 0, ss_hi = 0;
    int warned = 0;
    for (int k = 0; k < runs; ++k) {
      const BootstrapResult r = mean_bootstrap(x, b, 100 + static_cast<std::uint64_t>(k));
      said_lo += r.lower_mc_error[0] / runs;
      said_hi += r.upper_mc_error[0] / runs;
      s_lo += r.lower[0];
      ss_lo += r.lower[0] * r.lower[0];
      s_hi += r.upper[0];
      ss_hi += r.upper[0] * r.upper[0];
      warned += r.warnings.empty() ? 0 : 1;
      if (k == 0) CHECK(r.replicates_needed >= 200);  // 5 / 0.025: five replicates beyond each endpoint
    }
    const double sd_lo = std::sqrt((ss_lo - s_lo * s_lo / runs) / (runs - 1));
    const double sd_hi = std::sqrt((ss_hi - s_hi * s_hi / runs) / (runs - 1));
    INFO(key << ": said " << said_lo << ", " << said_hi << "; own spread " << sd_lo << ", " << sd_hi);
    // SciPy's spread over 400 bootstraps (itself known to about 4 %); the estimate is distribution-free
    // and reads the one or two outermost replicates at 50, so 25 % there, 15 % at 400
    const double tol = b == 50 ? 0.25 : 0.15;
    CHECK(said_lo == Approx(at(ref, key.c_str(), "lower_sd")).epsilon(tol));
    CHECK(said_hi == Approx(at(ref, key.c_str(), "upper_sd")).epsilon(tol));
    CHECK(sd_lo == Approx(at(ref, key.c_str(), "lower_sd")).epsilon(0.2));
    CHECK(sd_hi == Approx(at(ref, key.c_str(), "upper_sd")).epsilon(0.2));
    if (b == 50) CHECK(warned == runs);  // 50 replicates leave fewer than 5 beyond each 2.5 % endpoint: always said
  }
}

TEST_CASE("replicates side by side give the same numbers as one after another") {
  const Eigen::VectorXd x = data_of(reference());
  const BootstrapResult one = mean_bootstrap(x, 64, 9, 1);
  const BootstrapResult two = mean_bootstrap(x, 64, 9, 2);
  REQUIRE(one.thetas.rows() == two.thetas.rows());
  CHECK((one.thetas - two.thetas).cwiseAbs().maxCoeff() == 0.0);
  CHECK(one.lower[0] == two.lower[0]);
  CHECK(one.upper_mc_error[0] == two.upper_mc_error[0]);
  CHECK(one.evaluations == two.evaluations);
}

TEST_CASE("failed replicates are listed with their errors; a bootstrap with fewer than two left names the first") {
  const Eigen::VectorXd x = data_of(reference());
  std::vector<Parameter> p{{"m", 0.0, 5.0, 1.0}};
  BootstrapOptions o;
  o.replicates = 6;
  o.seed = 3;
  o.warm_start = true;
  // Replicates 2, 4 and 6 fail while building their objective (a degenerate resample would).
  int built = 0;
  ReplicateFactory some_fail = [&built](const std::vector<Eigen::VectorXd>& d) {
    if (++built % 2 == 0) throw smi::InvalidArgument("resample " + std::to_string(built) + " is degenerate");
    const Eigen::VectorXd y = d[0];
    return Replicate{[y](const Eigen::VectorXd& t) { return Evaluation{(y.array() - t[0]).square().mean(), {}}; }, {}, {}, {}};
  };
  const BootstrapResult r = bootstrap_calibration(p, Eigen::VectorXd::Constant(1, x.mean()), {x}, some_fail, o);
  CHECK(r.thetas.rows() == 3);
  CHECK(r.failed == 3);
  REQUIRE(r.failures.size() == 3);
  CHECK(r.failures[0].first == 2);
  CHECK(r.failures[0].second == "resample 2 is degenerate");
  CHECK(r.failures[2].first == 6);
  ReplicateFactory all_fail = [](const std::vector<Eigen::VectorXd>&) -> Replicate { throw smi::InvalidArgument("no data left"); };
  CHECK_THROWS_WITH(bootstrap_calibration(p, Eigen::VectorXd::Constant(1, x.mean()), {x}, all_fail, o),
                    "bootstrap: only 0 of 6 replicates succeeded (replicate 1: no data left)");
}
