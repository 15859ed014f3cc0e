// SPDX-License-Identifier: MIT
#pragma once
// The statistical calibration objective of Son et al. eq. (9) (docs/spec/algorithms.md §2, §7):
// θ holds the means and standard deviations of the unknown inputs; every input is mapped from
// a fixed CRN column (crn_mapping.hpp), the model runs once on the whole N×k input matrix, and
// the predicted outputs are compared with the experimental data response by response:
//   "pr"     Σ_r PR_r = Σ_r ∫|f_exp,r − f_pre,r| dy  (KDEs, normal-reference bandwidth, fixed grid)
//   "loglik" −Σ_r Σ_i log f_pre,r(y_exp,r,i)            (densities floored at 1e-300)
//   custom   any function of the predicted outputs (supplied by the caller).
#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/crn_mapping.hpp"
#include "kernels/stats/distribution.hpp"
#include "kernels/stats/grid.hpp"

namespace smi::improve {

/// One model input: its family and either fixed or calibrated mean and std.
struct InputSpec {
  std::string name;
  InputFamily family = InputFamily::normal;
  double mean = 0.0;     ///< used when mean_param < 0
  double std = 0.0;      ///< used when std_param < 0
  int mean_param = -1;   ///< index of the mean in θ, or -1 when fixed
  int std_param = -1;    ///< index of the std in θ, or -1 when fixed
  InputShape shape;      ///< fixed shape of the families beyond normal/lognormal/uniform
};

/// One observed response.
struct ResponseSpec {
  std::string name;
  Eigen::VectorXd data;     ///< the experimental observations (with a given f_exp: the points behind it)
  stats::DistributionPtr f_exp;    ///< experimental PDF; null = Gaussian KDE of data, normal-reference h
  std::optional<stats::Grid> grid; ///< PR grid; null = fixed at construction (see StatisticalObjective)
  bool f_exp_from_data = false;  ///< set when f_exp is built from data (then rebuilt by with_data)

  /// The measured mean and standard deviation: of the experimental PDF when it was given, else
  /// of the data (two or more points); {0, 0} when neither is given. Callers check sd > 0.
  std::pair<double, double> moments() const;
};

enum class MetricKind { pr, loglik, custom };
MetricKind parse_metric(std::string_view name);

/// Y = model(X): X is N×k (columns in the order of the inputs), Y is N×R (columns in the order
/// of the responses).
using Model = std::function<Eigen::MatrixXd(const Eigen::MatrixXd& X)>;
/// A caller-supplied metric of the predicted outputs Y (N×R).
using CustomMetric = std::function<Evaluation(const Eigen::MatrixXd& Y)>;

/// The smallest CRN sample a KDE of the predictions is built on.
inline constexpr Eigen::Index kMinCrnSize = 10;
/// model_step lies in (0, kMaxModelStep): a larger relative step leaves the local slope.
inline constexpr double kMaxModelStep = 0.1;

struct StatisticalOptions {
  Eigen::Index n = 2000;            ///< CRN sample size
  std::uint64_t seed = 0;
  CrnKind crn = CrnKind::random;
  MetricKind metric = MetricKind::pr;
  Eigen::Index grid_nodes = kDefaultGridNodes;  ///< nodes of the default PR grids
  std::string bandwidth = "silverman";  ///< bandwidth rule for the predicted KDEs
  double density_floor = 1e-300;    ///< loglik floor (spec §2.2)
  int threads = kDefaultThreads;    ///< KDE evaluation threads (or starts, replicates side by side)
};

class StatisticalObjective {
 public:
  /// Validates everything it can before any model run: families vs θ bounds (lognormal means
  /// must stay > 0), data finite and >= 2 points, parameter indices in range. The default PR grid
  /// of each response is fixed here from the data, f_exp and one model run at θ = start:
  /// [min − 6 h_max, max + 6 h_max] (spec §0). Mass of either PDF outside the grid is added to
  /// PR exactly (through the KDE CDF), so moving the prediction away never lowers PR.
  StatisticalObjective(std::vector<InputSpec> inputs, std::vector<ResponseSpec> responses, std::vector<Parameter> params,
                       Model model, StatisticalOptions opt, CustomMetric custom = {});

  Evaluation operator()(const Eigen::VectorXd& theta) const;

  /// dY_r/dX (N×k, columns in the order of the inputs) per response at the rows of X.
  using ModelJacobian = std::function<std::vector<Eigen::MatrixXd>(const Eigen::MatrixXd& X)>;
  /// Set when the model has a gradient (a Kriging's closed form, a model's own `gradient`).
  void set_model_jacobian(ModelJacobian j) { jacobian_ = std::move(j); }
  bool has_model_jacobian() const { return static_cast<bool>(jacobian_); }
  /// Without a model Jacobian: differentiate the model itself at the CRN sample. Each
  /// gradient is ONE model call on the stacked batch [X; X + h_1 e_1; ...; X + h_k e_k] (forward,
  /// k + 1 passes for the k inputs that carry a calibrated parameter) or [X; X ± h_j e_j] (central,
  /// 2k + 1), so a solver model runs the perturbed points as one parallel, resumable evaluation.
  /// The step of input j is rel_step times its scale at θ (its standard deviation, at least 1e-6 of
  /// its |mean|); the rows then go through the quantile derivatives, the KDE and the metric exactly
  /// as a model Jacobian would. A model whose outputs carry few digits (a solver's printed results)
  /// needs a larger rel_step (about the square root of their relative resolution).
  void set_model_differences(bool central, double rel_step);
  bool has_model_differences() const { return diff_step_ > 0.0; }
  /// The predictions at θ and dY/dX per response at its CRN inputs, from the model's Jacobian or
  /// its differences (one model call either way); throws when it has neither.
  std::pair<Eigen::MatrixXd, std::vector<Eigen::MatrixXd>> predict_with_jacobian(const Eigen::VectorXd& theta) const;
  /// Sample passes of the model so far (N rows each): one per objective evaluation, k + 1 (or
  /// 2k + 1) per gradient by model differences, less the passes the output cache saved.
  long model_passes() const { return passes_->load(); }
  /// The model's Jacobian at the rows of X, checked (one per response, N×k each, finite).
  std::vector<Eigen::MatrixXd> model_jacobian(const Eigen::MatrixXd& X) const;
  /// value_and_gradient works: metric PR or loglik, a bandwidth rule with a closed-form derivative
  /// ("silverman", "normal", "1.06", "scott", "robust", "mad"), and a model Jacobian. Not "lscv"
  /// or "sj": their h solves an optimisation or a fixed-point equation over all pairs of samples
  /// (its derivative by the implicit function theorem costs O(N²) per evaluation), nor a custom
  /// metric (a Lua function of the outputs gives no ∂metric/∂y): those calibrate on central
  /// differences of the objective.
  bool has_gradient() const;
  /// The objective (the same value as operator()) and its gradient in θ's own units, by the
  /// chain rule through the inputs' quantile functions, the model's Jacobian, the KDE (its
  /// bandwidth included) and the metric (objective_gradient.cpp).
  Evaluation value_and_gradient(const Eigen::VectorXd& theta, Eigen::VectorXd& grad) const;

  /// The model's N×R outputs at θ (CRN inputs), checked finite.
  Eigen::MatrixXd predict(const Eigen::VectorXd& theta) const { return run_model(theta); }
  /// Summaries of the predicted responses at θ for identifiability: per response the first four
  /// Hermite moments of the prediction standardised by the data's mean and standard deviation
  /// (f_exp's without data), each of unit variance per datum for normal data.
  Eigen::VectorXd summaries(const Eigen::VectorXd& theta) const;
  /// The N×k input sample at θ (CRN).
  Eigen::MatrixXd inputs_at(const Eigen::VectorXd& theta) const;
  /// Mean and std of every input at θ.
  std::vector<std::pair<double, double>> input_moments(const Eigen::VectorXd& theta) const;

  /// The summed PR at θ against each of several sets of experimental data (one vector per
  /// response; their plain KDEs, normal-reference bandwidth, are the experimental PDFs), the
  /// prediction's KDE computed once: the PR tolerance's resamples (pr_tolerance.hpp). One model
  /// run at most (none where θ's outputs are cached), on the calling thread; the sets are summed
  /// on `threads`. A degenerate set (all its points equal) gives NaN.
  std::vector<double> pr_sums_against(const Eigen::VectorXd& theta, const std::vector<std::vector<Eigen::VectorXd>>& data_sets,
                                      int threads) const;

  /// The same objective (same CRN, model, grids) with other experimental data (bootstrap, the
  /// PR tolerance): their plain KDEs are the experimental PDFs, also where a PDF was given with
  /// its points. Throws for a response given as a PDF alone.
  StatisticalObjective with_data(const std::vector<Eigen::VectorXd>& data) const;

  const std::vector<InputSpec>& inputs() const { return inputs_; }
  const std::vector<ResponseSpec>& responses() const { return responses_; }
  const std::vector<Parameter>& parameters() const { return params_; }
  const Eigen::MatrixXd& crn() const { return z_; }
  const StatisticalOptions& options() const { return opt_; }
  /// The KDE sums' threads (1 where evaluations themselves run side by side).
  void set_threads(int threads) { opt_.threads = threads; }
  /// Model calls so far (at most one per objective evaluation: none where the outputs are cached).
  long model_runs() const { return runs_->load(); }
  /// Densities floored by the loglik metric so far.
  long floored() const { return floored_->load(); }

 private:
  /// A PDF on a response's grid and its mass outside the grid.
  struct OnGrid {
    Eigen::VectorXd pdf;
    double outside = 0.0;
  };
  static OnGrid on_grid(const stats::Distribution& f, const stats::Grid& g);
  /// The KDE of predicted outputs y of response j (the objective's bandwidth rule) on its grid.
  OnGrid predicted_on_grid(Eigen::Index j, const Eigen::VectorXd& y) const;
  /// PR of response j, ∫|f_exp − f_pre| on its grid plus both PDFs' mass outside it (spec §0):
  /// the one place the objective's PR is written.
  double pr_part(Eigen::Index j, const OnGrid& predicted, const Eigen::VectorXd& exp_pdf, double exp_outside) const;
  Eigen::MatrixXd run_model(const Eigen::VectorXd& theta) const;
  /// Checks a model's output Y for the N×k inputs X (shape, finiteness), naming the response.
  void check_output(const Eigen::MatrixXd& Y, Eigen::Index rows, const Eigen::VectorXd& theta) const;
  /// Y at the CRN inputs X of θ and dY/dX per response by model differences (one model call).
  std::pair<Eigen::MatrixXd, std::vector<Eigen::MatrixXd>> differences(const Eigen::VectorXd& theta, const Eigen::MatrixXd& X) const;
  void prepare_responses(const Eigen::VectorXd& start);

  std::vector<InputSpec> inputs_;
  std::vector<ResponseSpec> responses_;
  std::vector<Parameter> params_;
  Model model_;
  StatisticalOptions opt_;
  CustomMetric custom_;
  ModelJacobian jacobian_;
  bool diff_central_ = false;
  double diff_step_ = 0.0;  ///< > 0: gradient by model differences (set_model_differences)
  Eigen::MatrixXd z_;
  std::vector<Eigen::VectorXd> f_exp_grid_;   // f_exp at each response's grid nodes
  std::vector<double> exp_outside_;           // f_exp mass outside each grid
  // Atomic: starts optimised side by side (OptimizerOptions::start_threads) share the objective.
  std::shared_ptr<std::atomic<long>> runs_ = std::make_shared<std::atomic<long>>(0);
  std::shared_ptr<std::atomic<long>> floored_ = std::make_shared<std::atomic<long>>(0);
  std::shared_ptr<std::atomic<long>> passes_ = std::make_shared<std::atomic<long>>(0);

  /// The model's last outputs by θ, bit for bit (the CRN inputs are a function of θ alone, so
  /// the same θ gives the same N×R outputs). SLSQP evaluates the value at a line-search trial and
  /// asks for the gradient at the accepted point, the same θ: with the outputs cached that
  /// gradient costs k model passes (the perturbed blocks), not k + 1, and an analytic gradient no
  /// model run. A few entries, so that starts run side by side do not evict each other at once;
  /// shared by copies (with_data: the same model and CRN give the same outputs).
  struct OutputCache {
    static constexpr std::size_t kEntries = 8;
    std::mutex mutex;
    std::vector<std::pair<Eigen::VectorXd, Eigen::MatrixXd>> entries;  ///< most recent last
  };
  /// The cached outputs at θ (true) or false.
  bool cached_output(const Eigen::VectorXd& theta, Eigen::MatrixXd& Y) const;
  void cache_output(const Eigen::VectorXd& theta, const Eigen::MatrixXd& Y) const;
  std::shared_ptr<OutputCache> cache_ = std::make_shared<OutputCache>();
};

}  // namespace smi::improve
