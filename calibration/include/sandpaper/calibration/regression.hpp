#pragma once
// Ordinary least squares with the statistics a regression table reports (Minsky 1995, Figures 19 and
// 20 print the same set): coefficients with standard errors, t-ratios and two-sided p, R^2 and
// adjusted R^2, residual standard error s, degrees of freedom, sums of squares, F-ratio and its p.
// Solved with Eigen (column-pivoting Householder QR); p-values from Boost.Math's t and F distributions.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace sandpaper::calibration {

enum class Constant {
  Fitted,         // y = b0 + sum b_i x_i; R^2 and F about the mean of y
  ThroughOrigin,  // y = sum b_i x_i (Figure 20's form); R^2 and F about zero (uncentred)
};

struct Coefficient {
  std::string name;  // "constant" for the intercept, else the predictor's name as given
  double value = 0;
  double se = 0;     // standard error: s * sqrt(diag((X'X)^-1))
  double t = 0;      // value / se (+-inf when se is 0)
  double p = 1;      // two-sided, Student's t with df_residual degrees of freedom
};

struct RegressionResult {
  bool has_constant = true;
  std::size_t n = 0;                  // observations
  int df_regression = 0;              // predictors (not counting the constant)
  int df_residual = 0;                // n - number of fitted coefficients
  std::vector<Coefficient> coefficients;  // the constant first (when fitted), then predictors in order
  double ss_regression = 0, ss_residual = 0;
  double ss_total = 0;                // about the mean with a constant, about zero through the origin
  double r_squared = 0;               // ss_regression / ss_total (uncentred through the origin)
  double r_squared_adjusted = 0;      // 1 - (ss_residual / df_residual) / (ss_total / (n - 1 or n))
  double s = 0;                       // residual standard error sqrt(ss_residual / df_residual)
  double f_ratio = 0;                 // (ss_regression / df_regression) / s^2
  double f_p = 1;                     // upper tail of F(df_regression, df_residual)
  std::vector<double> fitted, residuals;  // per observation

  // The coefficient called `name`; throws std::out_of_range if there is none.
  const Coefficient& coefficient(std::string_view name) const;
};

// Fits y on the predictors (each a column of n values, named by `names`). Throws
// std::invalid_argument when sizes disagree, a value is not finite, there are no residual degrees
// of freedom (n <= coefficients), or the predictors (with the constant) are collinear.
RegressionResult least_squares(const std::vector<std::string>& names, const std::vector<std::vector<double>>& predictors,
                               const std::vector<double>& y, Constant constant);

// True when `y` varies by no more than rounding: its sum of squares about its mean is at most
// 1e-20 of its sum of squares (or both are 0). A regression on it fits noise.
bool varies_too_little(const std::vector<double>& y);

// Two-sided p of a t-ratio with `df` degrees of freedom; upper-tail p of an F-ratio (Boost.Math).
double t_two_sided_p(double t, double df);
double f_upper_p(double f, double df1, double df2);

}  // namespace sandpaper::calibration
