// SPDX-License-Identifier: MIT
// DACE's objective psi(theta) = sigma2 |R|^(1/m) and d ln psi / d ln theta.
// With W = R^-1 - gamma gamma^T / sigma2 (normalised units), the envelope theorem for the GLS
// beta gives d(m ln sigma2 + ln|R|)/d theta_k = sum_ij W_ij dR_ij/dtheta_k, and every family
// has dR_ij/dtheta_k = g'(s_ij) D_k,ij, so the whole gradient is one GEMV over the pairs.
#include "kernels/surrogate/likelihood.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "platform/core/errors.hpp"

namespace smi::surrogate::kriging::detail {
namespace {

constexpr Eigen::Index kLeaf = 48;  // below this, plain triangular solves beat the recursion

/// L (lower triangular, the strictly upper half ignored) <- L^-1 by the 2 x 2 block recursion
/// [A 0; B C]^-1 = [A^-1 0; -C^-1 B A^-1, C^-1]: m^3/3 flops where a solve against I costs m^3.
void invert_lower_inplace(Eigen::Ref<Eigen::MatrixXd> L) {
  const Eigen::Index n = L.rows();
  if (n <= kLeaf) {
    Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
    L.triangularView<Eigen::Lower>().solveInPlace(I);
    L.triangularView<Eigen::Lower>() = I;
    return;
  }
  const Eigen::Index h = n / 2;
  auto A = L.topLeftCorner(h, h);
  auto B = L.bottomLeftCorner(n - h, h);
  auto C = L.bottomRightCorner(n - h, n - h);
  A.triangularView<Eigen::Lower>().solveInPlace<Eigen::OnTheRight>(B);  // B A^-1
  C.triangularView<Eigen::Lower>().solveInPlace(B);                    // C^-1 B A^-1
  B = -B;
  invert_lower_inplace(A);
  invert_lower_inplace(C);
}

/// L (lower) <- lower half of L^T L: [A 0; B C]^T [A 0; B C] = [A^T A + B^T B, .; C^T B, C^T C].
void ltl_lower_inplace(Eigen::Ref<Eigen::MatrixXd> L) {
  const Eigen::Index n = L.rows();
  if (n <= kLeaf) {
    const Eigen::MatrixXd T = L.triangularView<Eigen::Lower>();
    L.triangularView<Eigen::Lower>() = T.transpose() * T;
    return;
  }
  const Eigen::Index h = n / 2;
  auto A = L.topLeftCorner(h, h);
  auto B = L.bottomLeftCorner(n - h, h);
  auto C = L.bottomRightCorner(n - h, n - h);
  ltl_lower_inplace(A);
  A.selfadjointView<Eigen::Lower>().rankUpdate(B.transpose());  // + B^T B
  B = C.triangularView<Eigen::Lower>().transpose() * B;          // C^T B (before C is overwritten)
  ltl_lower_inplace(C);
}

}  // namespace

Problem::Problem(Eigen::MatrixXd S_, Eigen::VectorXd Y_, Trend t, Corr c)
    : S(std::move(S_)), Y(std::move(Y_)), corr(c) {
  F = trend_basis(t, S);
  const Eigen::Index m = S.rows(), n = S.cols();
  mu = (10.0 + static_cast<double>(m)) * std::numeric_limits<double>::epsilon();
  D.resize(m * (m - 1) / 2, n);
  Eigen::Index k = 0;
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = j + 1; i < m; ++i, ++k) {
      const Eigen::RowVectorXd d = S.row(i) - S.row(j);
      if (uses_abs(c))
        D.row(k) = d.cwiseAbs();
      else
        D.row(k) = d.cwiseAbs2();
    }
}

Factors factorize(const Problem& pb, const Eigen::VectorXd& theta, double nugget) {
  Factors f;
  const Eigen::Index m = pb.m(), p = pb.F.cols();
  f.s.noalias() = pb.D * theta;
  Eigen::ArrayXd r = f.s.array();
  corr_from_s(pb.corr, r);
  Eigen::MatrixXd R(m, m);
  Eigen::Index k = 0;
  for (Eigen::Index j = 0; j < m; ++j) {
    R(j, j) = 1.0 + pb.mu + nugget;
    for (Eigen::Index i = j + 1; i < m; ++i) R(i, j) = r[k++];  // LLT reads the lower half only
  }
  // In place: R's lower half becomes the factor (no copies of an m x m matrix per evaluation).
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(R);
  if (llt.info() != Eigen::Success) return f;
  R.triangularView<Eigen::StrictlyUpper>().setZero();
  f.C = std::move(R);
  const auto L = f.C.triangularView<Eigen::Lower>();
  for (Eigen::Index i = 0; i < m; ++i)
    if (!(f.C(i, i) > 0) || !std::isfinite(f.C(i, i))) return f;
  f.Ft = L.solve(pb.F);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(f.Ft);
  f.G = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  f.Q = qr.householderQ() * Eigen::MatrixXd::Identity(m, p);
  const Eigen::VectorXd dg = f.G.diagonal().cwiseAbs();
  if (!(dg.minCoeff() >= 1e-10 * dg.maxCoeff())) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(pb.F);
    const auto sv = svd.singularValues();
    if (sv(sv.size() - 1) <= 1e-15 * sv(0))
      throw InvalidArgument("F too ill conditioned: the trend's columns are (nearly) dependent on this design; "
                            "use a lower trend or more distinct points");
    return f;  // psi = +inf
  }
  const Eigen::VectorXd Yt = L.solve(pb.Y);
  f.beta = f.G.triangularView<Eigen::Upper>().solve(f.Q.transpose() * Yt);
  const Eigen::VectorXd rho = Yt - f.Ft * f.beta;
  f.sigma2 = rho.squaredNorm() / static_cast<double>(m);
  f.gamma = f.C.transpose().triangularView<Eigen::Upper>().solve(rho);
  const double logdet = 2.0 * f.C.diagonal().array().log().sum();
  if (!(f.sigma2 > 0)) f.sigma2 = std::numeric_limits<double>::min();  // exact interpolation of a constant
  f.log_psi = std::log(f.sigma2) + logdet / static_cast<double>(m);
  f.psi = std::exp(f.log_psi);
  f.ok = std::isfinite(f.log_psi);
  return f;
}

Eigen::VectorXd log_psi_gradient(const Problem& pb, const Factors& f, const Eigen::VectorXd& theta, double nugget,
                                 bool with_nugget) {
  const Eigen::Index m = pb.m(), n = theta.size();
  // R^-1 = C^-T C^-1, lower half only, in m^3/3 + m^3/3 flops (LAPACK's potri split).
  Eigen::MatrixXd W = f.C;
  invert_lower_inplace(W);
  ltl_lower_inplace(W);
  Eigen::ArrayXd slope;
  corr_slope(pb.corr, f.s.array(), slope);
  Eigen::VectorXd a(f.s.size());
  Eigen::Index k = 0;
  const double is2 = 1.0 / f.sigma2;
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = j + 1; i < m; ++i, ++k) a[k] = (W(i, j) - f.gamma[i] * f.gamma[j] * is2) * slope[k];
  Eigen::VectorXd g(n + (with_nugget ? 1 : 0));
  g.head(n) = (2.0 / static_cast<double>(m)) * (pb.D.transpose() * a).cwiseProduct(theta);
  if (with_nugget) {
    double tr = 0;
    for (Eigen::Index i = 0; i < m; ++i) tr += W(i, i) - f.gamma[i] * f.gamma[i] * is2;
    g[n] = tr / static_cast<double>(m) * nugget;
  }
  return g;
}

}  // namespace smi::surrogate::kriging::detail
