// SPDX-License-Identifier: MIT
#pragma once
// Transitional Markov chain Monte Carlo (Ching & Chen 2007; docs/spec/algorithms.md §9.2): the
// posterior p(θ|Y) ∝ L(θ) π(θ) and the log evidence log Z = log ∫ L π dθ.
//
// Particles drawn from the prior are carried through tempered targets π(θ) L(θ)^β_k with
// 0 = β_0 < β_1 < ... < β_m = 1. At each stage Δβ is chosen so that the plausibility weights
// w_j = L(θ_j)^Δβ have a coefficient of variation equal to the target (1: about half the
// particles keep weight); log Z += log mean_j w_j. The particles are resampled by weight and each
// resampled particle seeds a Metropolis chain with the Gaussian proposal c² Σ_k (Σ_k the weighted
// sample covariance), run sweeps until the chains have moved and forgotten their seeds; c adapts
// to an acceptance rate near 0.23.
//
// Batches: the log-likelihood takes a matrix of θ rows and returns one value per row; it is
// called once per sweep of all chains (points outside the prior's support are rejected without
// a call). Parallel: a thread-safe callback is called on blocks of rows over the thread pool;
// the values of a row never depend on the split, so the results do not depend on threads.
// Same seed, same numbers.
//
// Monte Carlo error of log Z: each stage adds var(mean w)/mean(w)², with var(mean w) estimated
// over the families of particles that descend from one resampled seed (particles of one family
// are correlated; the families are independent given the previous stage), summed over stages.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "kernels/improve/bayes_prior.hpp"
#include "platform/core/cancel.hpp"

namespace smi::improve {

/// log L(θ) per row of Theta (rows = points). −∞ is a zero likelihood; NaN and +∞ are errors.
using BatchLogLikelihood = std::function<Eigen::VectorXd(const Eigen::MatrixXd& Theta)>;

/// The fewest particles a stage can be reweighted and resampled with.
inline constexpr int kMinParticles = 10;

struct TmcmcOptions {
  Eigen::Index samples = 1000;  ///< particles per stage (and posterior samples)
  int max_stages = 50;          ///< stop (not converged) when β has not reached 1 by then
  double target_cov = 1.0;      ///< coefficient of variation of the weights that fixes Δβ
  int min_sweeps = 2;           ///< Metropolis sweeps of all chains per stage, at least
  int max_sweeps = 50;          ///< and at most
  double moves = 2.0;           ///< sweeps run until each chain has moved about this often
  /// and until the chains' end points keep at most this correlation with their seeds (the
  /// chains forget where they started: in 10 dimensions that takes 10 to 30 sweeps)
  double target_correlation = 0.3;
  double target_acceptance = 0.23;  ///< the proposal scale adapts towards it
  std::uint64_t seed = 0;
  int threads = 1;                  ///< for a thread-safe callback: row blocks in parallel
  bool callback_thread_safe = false;  ///< set for C++ callbacks that may run on several threads
};

/// What happened at one stage (its tempering step and the chains that followed it).
struct TmcmcStage {
  double beta = 0.0;        ///< β after this stage
  double log_mean_w = 0.0;  ///< log mean_j w_j (its share of log Z)
  double log_z_var = 0.0;   ///< its Monte Carlo variance
  double ess = 0.0;         ///< effective sample size of the weights, (Σw)²/Σw²
  double acceptance = 0.0;  ///< acceptance rate over the stage's sweeps
  int sweeps = 0;
  double scale = 0.0;       ///< proposal scale c at the end of the stage
  /// Mean over parameters of the correlation between each chain's seed and its end point: near
  /// 0 when the chains forget where they started, near 1 when they barely move.
  double chain_correlation = 0.0;
};

struct TmcmcResult {
  Eigen::MatrixXd samples;   ///< posterior samples, rows = points (equally weighted)
  Eigen::VectorXd loglik;    ///< log L at each sample
  Eigen::VectorXd logprior;  ///< log π at each sample
  double log_evidence = 0.0;
  double log_evidence_error = 0.0;  ///< Monte Carlo standard error of log_evidence
  std::vector<TmcmcStage> stages;
  long evaluations = 0;  ///< log-likelihood values computed (rows passed to the callback)
  long calls = 0;        ///< calls of the callback
  bool converged = false;
  std::vector<std::string> reasons;  ///< why not converged, or what to watch; empty when all is well
  Eigen::Index map_index = 0;  ///< the sample with the highest log L + log π
};

/// Runs TMCMC. Throws InvalidArgument for bad options, or when the likelihood returns NaN / +∞
/// (the row named) or is zero at every prior draw; smi::Interrupted when `stop` is set.
TmcmcResult tmcmc(const PriorSet& prior, const BatchLogLikelihood& loglik, const TmcmcOptions& o,
                  const cancel::Token& stop = cancel::process_token());

}  // namespace smi::improve
