#include "sandpaper/experiment/psychometric.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>

namespace sandpaper::experiment {
namespace {

const boost::math::normal kNormal;

double p_of(double sigma, double increment) {
  const double p = boost::math::cdf(kNormal, std::log1p(increment) / (sigma * std::sqrt(2.0)));
  return std::clamp(p, 1e-12, 1 - 1e-12);
}

double log_likelihood(const std::vector<IncrementCount>& data, double sigma) {
  double ll = 0;
  for (const auto& d : data) {
    const double p = p_of(sigma, d.increment);
    ll += d.correct * std::log(p) + (d.trials - d.correct) * std::log(1 - p);
  }
  return ll;
}

double weber_of(double sigma) {
  return std::expm1(sigma * std::sqrt(2.0) * boost::math::quantile(kNormal, 0.75));
}

}  // namespace

double PsychometricFit::p_correct(double increment) const { return p_of(sigma, increment); }

PsychometricFit fit_two_interval(const std::vector<IncrementCount>& data) {
  int trials = 0, correct = 0;
  for (const auto& d : data) {
    if (!(d.increment > 0)) throw std::invalid_argument("two-interval fit: increments must be > 0");
    trials += d.trials;
    correct += d.correct;
  }
  if (trials == 0) throw std::invalid_argument("two-interval fit: no trials");
  if (correct == trials)
    throw std::invalid_argument("two-interval fit: every answer was correct; add smaller increments to find the JND");
  if (2 * correct <= trials)
    throw std::invalid_argument("two-interval fit: answers are at chance level; add larger increments to find the JND");
  // Search log sigma over 1e-4 .. 1e2 (Weber fractions from 0.01 % to far beyond any increment).
  const double lo = std::log(1e-4), hi = std::log(1e2);
  auto neg = [&](double ls) { return -log_likelihood(data, std::exp(ls)); };
  const auto [best_ls, best_neg] = boost::math::tools::brent_find_minima(neg, lo, hi, 40);
  PsychometricFit f;
  f.sigma = std::exp(best_ls);
  f.log_likelihood = -best_neg;
  f.trials = trials;
  f.weber_fraction = weber_of(f.sigma);
  // The interval: log sigma where the deviance rises by the chi-square(1) 95 % point, 3.841.
  const double crit = 3.841458820694124 / 2;
  auto excess = [&](double ls) { return neg(ls) - best_neg - crit; };
  boost::math::tools::eps_tolerance<double> tol(40);
  auto bound = [&](double from, double to) {
    if (excess(to) < 0) return std::numeric_limits<double>::quiet_NaN();  // not reached inside the range
    std::uintmax_t it = 100;
    const auto r = boost::math::tools::bisect(excess, std::min(from, to), std::max(from, to), tol, it);
    return std::exp((r.first + r.second) / 2);
  };
  const double s_low = bound(best_ls, lo), s_high = bound(best_ls, hi);
  f.weber_low = std::isnan(s_low) ? 0.0 : weber_of(s_low);
  f.weber_high = std::isnan(s_high) ? std::numeric_limits<double>::infinity() : weber_of(s_high);
  return f;
}

}  // namespace sandpaper::experiment
