// Long surrogate kernels stop when the run is cancelled (issue 14 item 5): LHS optimisation,
// the Kriging likelihood search and block prediction throw smi::Interrupted with the reason.
#include <catch2/catch.hpp>

#include "kernels/core/cancel.hpp"
#include "kernels/core/errors.hpp"
#include "kernels/surrogate/doe.hpp"
#include "kernels/surrogate/kriging.hpp"

using namespace smi;

namespace {
struct Interrupt {
  Interrupt() { cancel::request_interrupt(); }
  ~Interrupt() { cancel::reset(); }
};
}  // namespace

TEST_CASE("LHS optimisation stops when interrupted") {
  cancel::reset();
  doe::LhsOptions o;
  o.iterations = 100000;
  Interrupt i;
  REQUIRE_THROWS_WITH(doe::lhs(300, 10, 1, o), "interrupted");
}

TEST_CASE("a Kriging ML fit and a prediction stop when the deadline has passed") {
  cancel::reset();
  Eigen::MatrixXd X = doe::lhs(40, 2, 3);
  Eigen::VectorXd y = X.col(0).array().sin() + X.col(1).array().square();
  const kriging::Model m = kriging::fit(X, y);  // before: runs to the end
  cancel::set_deadline(cancel::Clock::now() - std::chrono::milliseconds(1), 1);
  REQUIRE_THROWS_WITH(kriging::fit(X, y), Catch::StartsWith("timeout: "));
  REQUIRE_THROWS_AS(kriging::predict(m, X, 2), Interrupted);
  cancel::reset();
  REQUIRE(kriging::predict(m, X, 2).mean.size() == 40);
}
