// SPDX-License-Identifier: MIT
#pragma once
// Seeded random numbers that are the same on every run, build and standard library.
// xoshiro256** (Blackman & Vigna 2018) seeded through splitmix64; normals by inversion of the
// standard normal CDF (normal.hpp), never std::normal_distribution, whose output is
// implementation-defined.
#include <Eigen/Core>
#include <cstdint>
#include <string_view>

namespace smi {

class Rng {
 public:
  /// A generator for `seed`; `stream` selects an independent sequence for the same seed
  /// (use one stream per study stage so that stages do not shift each other's numbers).
  explicit Rng(std::uint64_t seed, std::uint64_t stream = 0);

  /// A child generator named by a label, independent of this one's current position.
  static Rng derive(std::uint64_t seed, std::string_view label);

  std::uint64_t next_u64();
  /// Uniform on the open interval (0, 1): never exactly 0 or 1, so quantiles stay finite.
  double uniform01();
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  /// Standard normal by inversion: z = Phi^-1(U).
  double normal();
  /// Integer uniform on [lo, hi] inclusive, without modulo bias.
  std::int64_t integer(std::int64_t lo, std::int64_t hi);

  Eigen::VectorXd uniform(Eigen::Index n, double lo = 0.0, double hi = 1.0);
  Eigen::VectorXd normal(Eigen::Index n, double mean = 0.0, double sd = 1.0);
  Eigen::MatrixXd normal_matrix(Eigen::Index rows, Eigen::Index cols);
  Eigen::MatrixXd uniform_matrix(Eigen::Index rows, Eigen::Index cols);

 private:
  std::uint64_t s_[4];
};

/// FNV-1a 64-bit hash of a label, used to derive named streams.
std::uint64_t hash_label(std::string_view label);

}  // namespace smi
