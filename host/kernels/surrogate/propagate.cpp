// Common-random-number samples for propagation, screening and calibration.
#include "surrogate/propagate.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "core/rng.hpp"

namespace smi::propagate {

Eigen::VectorXd crn_uniforms(const std::string& name, Eigen::Index n, std::uint64_t seed, const std::string& stream) {
  Rng rng = Rng::derive(seed, stream + "/" + name);
  return rng.uniform(n);
}

Eigen::MatrixXd crn_sample(const std::vector<Input>& inputs, Eigen::Index n, std::uint64_t seed,
                           const std::string& stream) {
  if (n < 1) throw InvalidArgument("sample size n must be at least 1, got " + std::to_string(n));
  if (inputs.empty()) throw InvalidArgument("no inputs to sample");
  Eigen::MatrixXd X(n, static_cast<Eigen::Index>(inputs.size()));
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    const Input& in = inputs[k];
    if (!in.dist) {
      if (!std::isfinite(in.value)) throw InvalidArgument("input '" + in.name + "' is a constant that is not finite");
      X.col(static_cast<Eigen::Index>(k)).setConstant(in.value);
      continue;
    }
    X.col(static_cast<Eigen::Index>(k)) = in.dist->quantile(crn_uniforms(in.name, n, seed, stream));
    if (!X.col(static_cast<Eigen::Index>(k)).allFinite())
      throw InvalidArgument("input '" + in.name + "' (" + in.dist->describe() + ") gave non-finite quantiles");
  }
  return X;
}

}  // namespace smi::propagate
