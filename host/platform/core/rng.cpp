// SPDX-License-Identifier: MIT
#include "platform/core/rng.hpp"

#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"

namespace smi {
namespace {

std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

inline std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

std::uint64_t hash_label(std::string_view label) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : label) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

Rng::Rng(std::uint64_t seed, std::uint64_t stream) {
  // Mix the stream into the seed so that (seed, stream) pairs give unrelated states.
  std::uint64_t x = seed ^ (stream * 0xd1b54a32d192ed03ULL);
  for (auto& s : s_) s = splitmix64(x);
}

Rng Rng::derive(std::uint64_t seed, std::string_view label) { return Rng(seed, hash_label(label)); }

std::uint64_t Rng::next_u64() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Rng::uniform01() {
  // 53 random bits, centred in their cell: (k + 0.5) / 2^53 lies strictly inside (0, 1).
  return (static_cast<double>(next_u64() >> 11) + 0.5) * 0x1.0p-53;
}

double Rng::normal() { return normal_quantile(uniform01()); }

std::int64_t Rng::integer(std::int64_t lo, std::int64_t hi) {
  if (hi < lo) throw InvalidArgument("integer range is empty: lo > hi");
  // In unsigned arithmetic: hi - lo overflows int64 for ranges wider than 2^63 (the full range
  // gave a division by zero once the compiler had assumed no signed overflow).
  const std::uint64_t span = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo) + 1;
  if (span == 0) return static_cast<std::int64_t>(next_u64());  // full 64-bit range
  // Rejection sampling (Lemire's threshold) removes the modulo bias.
  const std::uint64_t limit = (0 - span) % span;
  for (;;) {
    const std::uint64_t r = next_u64();
    if (r >= limit) return static_cast<std::int64_t>(static_cast<std::uint64_t>(lo) + r % span);
  }
}

Eigen::VectorXd Rng::uniform(Eigen::Index n, double lo, double hi) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = uniform(lo, hi);
  return v;
}

Eigen::VectorXd Rng::normal(Eigen::Index n, double mean, double sd) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = mean + sd * normal();
  return v;
}

Eigen::MatrixXd Rng::normal_matrix(Eigen::Index rows, Eigen::Index cols) {
  // Filled row by row so that the first k rows do not depend on the number of rows asked.
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j) m(i, j) = normal();
  return m;
}

Eigen::MatrixXd Rng::uniform_matrix(Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j) m(i, j) = uniform01();
  return m;
}

}  // namespace smi
