// SPDX-License-Identifier: MIT
// Long surrogate kernels stop when the run is cancelled: LHS optimisation,
// the Kriging likelihood search and block prediction throw smi::Interrupted with the reason.
#include <catch2/catch.hpp>

#include "kernels/surrogate/doe.hpp"
#include "kernels/surrogate/kriging.hpp"
#include "platform/core/cancel.hpp"
#include "platform/core/errors.hpp"

using namespace smi;

namespace {
struct Interrupt {
  Interrupt() { cancel::request_interrupt(); }
  ~Interrupt() { cancel::reset(); }
};
}  // namespace

TEST_CASE("LHS optimisation stops when interrupted") {
  cancel::reset();
  surrogate::doe::LhsOptions o;
  o.iterations = 100000;
  Interrupt i;
  REQUIRE_THROWS_WITH(surrogate::doe::lhs(300, 10, 1, o), "interrupted");
}

TEST_CASE("a Kriging ML fit and a prediction stop when the deadline has passed") {
  cancel::reset();
  Eigen::MatrixXd X = surrogate::doe::lhs(40, 2, 3);
  Eigen::VectorXd y = X.col(0).array().sin() + X.col(1).array().square();
  const surrogate::kriging::Model m = surrogate::kriging::fit(X, y);  // before: runs to the end
  cancel::set_deadline(cancel::Clock::now() - std::chrono::milliseconds(1), 1);
  REQUIRE_THROWS_WITH(surrogate::kriging::fit(X, y), Catch::StartsWith("timeout: "));
  REQUIRE_THROWS_AS(surrogate::kriging::predict(m, X, 2), Interrupted);
  cancel::reset();
  REQUIRE(surrogate::kriging::predict(m, X, 2).mean.size() == 40);
}
