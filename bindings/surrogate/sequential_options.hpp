// SPDX-License-Identifier: MIT
#pragma once
// The option schema of smi.kriging.sequential (luax/option_schema.hpp): the loop's and the
// Krigings' options into kriging::SequentialOptions; model, design, candidates, weights, rmse and
// inputs are read by hand (sequential.cpp). doc.cpp lists them.
#include <Eigen/Core>

#include <string>
#include <vector>

#include "kernels/surrogate/sequential_design.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::surrogate {

struct SequentialArgs {
  smi::surrogate::kriging::SequentialOptions so;  ///< batch, max, q2, and the fits' trend, corr, seed
  std::vector<std::string> input_names;
  Eigen::MatrixXd design, candidates;
  Eigen::VectorXd weights;
};

const lua::Schema<SequentialArgs>& sequential_schema();

}  // namespace smi::bind::surrogate
