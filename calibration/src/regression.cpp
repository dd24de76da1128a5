// Least squares by column-pivoting QR (Eigen): well conditioned even when log force and log period
// are correlated, and the rank it reports tells collinear predictors apart from a fit.
#include "sandpaper/calibration/regression.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace sandpaper::calibration {

const Coefficient& RegressionResult::coefficient(std::string_view name) const {
  for (const auto& c : coefficients)
    if (c.name == name) return c;
  throw std::out_of_range("regression has no coefficient `" + std::string(name) + "`");
}

double t_two_sided_p(double t, double df) {
  if (std::isnan(t)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(t)) return 0.0;
  boost::math::students_t dist(df);
  return 2.0 * boost::math::cdf(boost::math::complement(dist, std::abs(t)));
}

double f_upper_p(double f, double df1, double df2) {
  if (std::isnan(f)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(f)) return 0.0;
  if (f <= 0) return 1.0;
  boost::math::fisher_f dist(df1, df2);
  return boost::math::cdf(boost::math::complement(dist, f));
}

RegressionResult least_squares(const std::vector<std::string>& names, const std::vector<std::vector<double>>& predictors,
                               const std::vector<double>& y, Constant constant) {
  if (names.size() != predictors.size()) throw std::invalid_argument("least_squares: one name per predictor");
  if (predictors.empty() && constant == Constant::ThroughOrigin)
    throw std::invalid_argument("least_squares: nothing to fit (no predictor, no constant)");
  const auto n = static_cast<Eigen::Index>(y.size());
  for (const auto& col : predictors)
    if (static_cast<Eigen::Index>(col.size()) != n) throw std::invalid_argument("least_squares: predictor length differs from y");
  const bool with_constant = constant == Constant::Fitted;
  const auto k = static_cast<Eigen::Index>(predictors.size() + (with_constant ? 1 : 0));
  if (n <= k)
    throw std::invalid_argument("least_squares: " + std::to_string(n) + " observations for " + std::to_string(k) +
                                " coefficients leaves no residual degrees of freedom");

  Eigen::MatrixXd X(n, k);
  Eigen::VectorXd Y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index j = 0;
    if (with_constant) X(i, j++) = 1.0;
    for (const auto& col : predictors) X(i, j++) = col[static_cast<std::size_t>(i)];
    Y(i) = y[static_cast<std::size_t>(i)];
  }
  if (!X.allFinite() || !Y.allFinite()) throw std::invalid_argument("least_squares: a value is not finite");

  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
  if (qr.rank() < k) throw std::invalid_argument("least_squares: the predictors are collinear (rank " +
                                                 std::to_string(qr.rank()) + " of " + std::to_string(k) + ")");
  const Eigen::VectorXd beta = qr.solve(Y);
  const Eigen::VectorXd fitted = X * beta;
  const Eigen::VectorXd resid = Y - fitted;

  // (X'X)^-1 = P R^-1 R^-T P' from X P = Q R.
  const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(k, k).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd Rinv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(k, k));
  const Eigen::MatrixXd P = qr.colsPermutation();
  const Eigen::MatrixXd xtx_inv = P * (Rinv * Rinv.transpose()) * P.transpose();

  RegressionResult r;
  r.has_constant = with_constant;
  r.n = static_cast<std::size_t>(n);
  r.df_regression = static_cast<int>(predictors.size());
  r.df_residual = static_cast<int>(n - k);
  r.ss_residual = resid.squaredNorm();
  r.ss_total = with_constant ? (Y.array() - Y.mean()).matrix().squaredNorm() : Y.squaredNorm();
  // Summed directly rather than as total - residual: the difference of two nearly equal sums came
  // out negative when the regression explains nothing, and so did the F ratio.
  r.ss_regression = with_constant ? (fitted.array() - Y.mean()).matrix().squaredNorm() : fitted.squaredNorm();
  r.r_squared = r.ss_total > 0 ? std::clamp(r.ss_regression / r.ss_total, 0.0, 1.0) : 0.0;
  const double df_total = static_cast<double>(with_constant ? n - 1 : n);
  r.r_squared_adjusted = r.ss_total > 0 ? 1.0 - (r.ss_residual / r.df_residual) / (r.ss_total / df_total) : 0.0;
  const double s2 = r.ss_residual / r.df_residual;
  r.s = std::sqrt(s2);
  if (r.df_regression > 0) {
    r.f_ratio = s2 > 0 ? (r.ss_regression / r.df_regression) / s2 : std::numeric_limits<double>::infinity();
    r.f_p = f_upper_p(r.f_ratio, r.df_regression, r.df_residual);
  }
  for (Eigen::Index j = 0; j < k; ++j) {
    Coefficient c;
    c.name = with_constant ? (j == 0 ? "constant" : names[static_cast<std::size_t>(j - 1)]) : names[static_cast<std::size_t>(j)];
    c.value = beta(j);
    c.se = std::sqrt(s2 * xtx_inv(j, j));
    c.t = c.se > 0 ? c.value / c.se : std::copysign(std::numeric_limits<double>::infinity(), c.value);
    c.p = t_two_sided_p(c.t, r.df_residual);
    r.coefficients.push_back(std::move(c));
  }
  r.fitted.assign(fitted.data(), fitted.data() + n);
  r.residuals.assign(resid.data(), resid.data() + n);
  return r;
}

bool varies_too_little(const std::vector<double>& y) {
  if (y.empty()) return true;
  double mean = 0, squares = 0;
  for (double v : y) mean += v / static_cast<double>(y.size());
  double about_mean = 0;
  for (double v : y) {
    about_mean += (v - mean) * (v - mean);
    squares += v * v;
  }
  return about_mean <= 1e-20 * squares;
}

}  // namespace sandpaper::calibration
