// Magnitude estimation with a free modulus (Minsky 1995, 5.2.3: "Pick a number that best matches the
// roughness ... You cannot use zero or negative numbers"): each subject picks their own scale, so
// estimates are comparable only as ratios. Geometric-mean normalisation puts every subject on a
// common scale before estimates are averaged (Lane, Catania & Stevens 1961), and geometric means
// are the averages that respect ratios (docs/CALIBRATION.md, "Fitting").
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "sandpaper/calibration/csv.hpp"
#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"

namespace sandpaper::calibration {
namespace {

const std::vector<std::string> kColumns = {"subject", "stimulus", "force_N", "period_mm", "response"};

MagnitudeEstimationData from_table(const CsvTable& t) {
  require_columns(t, kColumns);
  const auto c_subject = *t.column("subject"), c_stimulus = *t.column("stimulus"), c_force = *t.column("force_N"),
             c_period = *t.column("period_mm"), c_response = *t.column("response");
  MagnitudeEstimationData d;
  d.path = t.path;
  for (const auto& row : t.rows) {
    Trial tr;
    tr.line = row.line;
    tr.subject = row.fields[c_subject];
    tr.stimulus = row.fields[c_stimulus];
    if (tr.subject.empty()) throw FitError(t.path, row.line, "`subject` is empty; every trial names its subject");
    if (tr.stimulus.empty()) throw FitError(t.path, row.line, "`stimulus` is empty; every trial names its stimulus");
    tr.x = number_field(t, row, c_force);
    if (!(tr.x > 0))
      throw FitError(t.path, row.line, fmt::format("force_N is {:g}: forces must be positive (the fit takes log10 of the force)", tr.x));
    const double period_mm = number_field(t, row, c_period);
    if (!(period_mm > 0))
      throw FitError(t.path, row.line, fmt::format("period_mm is {:g}: periods must be positive (the period regression takes log10 of it)", period_mm));
    tr.period_m = period_mm * 1e-3;
    const std::string& r = row.fields[c_response];
    if (!r.empty() && r != "NA") {
      const double v = number_field(t, row, c_response);
      if (!(v > 0))
        throw FitError(t.path, row.line,
                       fmt::format("response is {:g}: magnitude estimates must be positive (log undefined); "
                                   "leave the cell empty for a trial without an answer",
                                   v));
      tr.response = v;
    }
    d.trials.push_back(std::move(tr));
  }
  if (d.trials.empty()) throw FitError(t.path, t.header_line, "no trials: the header is followed by no data rows");
  return d;
}

double log_mean(const std::vector<double>& logs) {
  double s = 0;
  for (double v : logs) s += v;
  return s / static_cast<double>(logs.size());
}

}  // namespace

MagnitudeEstimationData parse_magnitude_estimation_csv(std::string_view text, const std::string& path) {
  return from_table(parse_csv(text, path));
}

MagnitudeEstimationData read_magnitude_estimation_csv(const std::filesystem::path& path) {
  return from_table(read_csv(path));
}

MagnitudeEstimationFit fit_magnitude_estimation(const MagnitudeEstimationData& data, Normalisation normalisation) {
  const std::string& file = data.path;
  MagnitudeEstimationFit f;
  f.path = file;
  f.predictor = data.predictor;
  f.normalisation = normalisation;
  const std::string& what = data.predictor.name;  // "force", "stiffness", ...
  const std::string unit = data.predictor.unit == "1" ? "" : " " + data.predictor.unit;
  if (data.trials.empty()) throw FitError(file, 0, "no trials");

  // Stimuli and subjects in order of first appearance; a stimulus is one force and one period.
  std::map<std::string, std::size_t> stim_index, subj_index;
  std::vector<int> stim_first_line;
  std::vector<std::vector<double>> subj_logs;    // log10 of each subject's answered estimates
  std::vector<int> subj_first_line;
  std::map<std::pair<std::size_t, std::size_t>, int> trials_per_pair;
  for (const auto& tr : data.trials) {
    auto [si, new_stim] = stim_index.try_emplace(tr.stimulus, f.stimuli.size());
    if (new_stim) {
      f.stimuli.push_back({tr.stimulus, tr.x, tr.period_m, 0, 0});
      stim_first_line.push_back(tr.line);
    } else {
      const auto& s = f.stimuli[si->second];
      const auto differs = [](double a, double b) { return std::abs(a - b) > 1e-9 * std::max(std::abs(a), std::abs(b)); };
      if (differs(s.x, tr.x) || differs(s.period_m, tr.period_m))
        throw FitError(file, tr.line,
                       fmt::format("stimulus `{}` is {:g}{}, {:g} mm here but {:g}{}, {:g} mm on line {}: a stimulus has one "
                                   "{} and one period (give different stimuli different names)",
                                   tr.stimulus, tr.x, unit, tr.period_m * 1e3, s.x, unit, s.period_m * 1e3,
                                   stim_first_line[si->second], what));
    }
    auto [ji, new_subj] = subj_index.try_emplace(tr.subject, f.subjects.size());
    if (new_subj) {
      f.subjects.push_back({tr.subject, 0, 0, 0, std::nullopt});
      subj_logs.emplace_back();
      subj_first_line.push_back(tr.line);
    }
    auto& subj = f.subjects[ji->second];
    ++subj.trials;
    ++f.trials;
    ++trials_per_pair[{ji->second, si->second}];
    if (tr.response) {
      ++subj.answered;
      ++f.answered;
      subj_logs[ji->second].push_back(std::log10(*tr.response));
    }
  }
  for (const auto& [pair, count] : trials_per_pair) f.runs = std::max(f.runs, count);

  for (std::size_t j = 0; j < f.subjects.size(); ++j)
    if (f.subjects[j].answered == 0)
      throw FitError(file, subj_first_line[j],
                     fmt::format("subject `{}` has no usable responses (all {} of their trials have an empty response); "
                                 "remove the subject or fill in their estimates",
                                 f.subjects[j].subject, f.subjects[j].trials));

  // A free modulus is known only from two or more stimuli: a subject who answered one has their one
  // estimate divided by itself, and with every subject so the means were all equal and the fit
  // rounding noise (F28).
  if (normalisation == Normalisation::GeometricMean) {
    std::vector<std::set<std::string>> answered_stimuli(f.subjects.size());
    for (const auto& tr : data.trials)
      if (tr.response) answered_stimuli[subj_index.at(tr.subject)].insert(tr.stimulus);
    for (std::size_t j = 0; j < f.subjects.size(); ++j)
      if (answered_stimuli[j].size() < 2)
        throw FitError(file, subj_first_line[j],
                       fmt::format("subject `{}` answered one stimulus only (`{}`): their estimates are divided by "
                                   "their own geometric mean, so one stimulus says nothing; remove the subject or give "
                                   "them two or more stimuli",
                                   f.subjects[j].subject, *answered_stimuli[j].begin()));
  }

  // Geometric-mean normalisation: log r' = log r - log GM_subject + log GM_grand, where GM_grand is
  // the geometric mean of the subjects' geometric means (each subject weighs the same).
  std::vector<double> offset(f.subjects.size(), 0.0);
  double grand_log = 0;
  for (std::size_t j = 0; j < f.subjects.size(); ++j) {
    const double m = log_mean(subj_logs[j]);
    f.subjects[j].geometric_mean = std::pow(10.0, m);
    grand_log += m / static_cast<double>(f.subjects.size());
  }
  f.grand_geometric_mean = std::pow(10.0, grand_log);
  if (normalisation == Normalisation::GeometricMean)
    for (std::size_t j = 0; j < f.subjects.size(); ++j) offset[j] = grand_log - std::log10(f.subjects[j].geometric_mean);

  // Per stimulus: geometric mean over subjects and runs of the normalised estimates. Per subject
  // and stimulus too, for the subjects' own slopes.
  const std::size_t ns = f.stimuli.size();
  std::vector<double> stim_sum(ns, 0.0);
  std::vector<std::vector<double>> subj_stim_sum(f.subjects.size(), std::vector<double>(ns, 0.0));
  std::vector<std::vector<int>> subj_stim_n(f.subjects.size(), std::vector<int>(ns, 0));
  for (const auto& tr : data.trials) {
    if (!tr.response) continue;
    const std::size_t i = stim_index.at(tr.stimulus), j = subj_index.at(tr.subject);
    const double l = std::log10(*tr.response) + offset[j];
    stim_sum[i] += l;
    ++f.stimuli[i].estimates;
    subj_stim_sum[j][i] += l;
    ++subj_stim_n[j][i];
  }
  for (std::size_t i = 0; i < ns; ++i)
    if (f.stimuli[i].estimates == 0)
      throw FitError(file, stim_first_line[i],
                     fmt::format("stimulus `{}` has no answered trial; it cannot be averaged (remove it or add estimates)",
                                 f.stimuli[i].stimulus));

  // What a fit of log estimate on log x needs: three stimuli (one residual degree of freedom)
  // at two or more levels of x.
  if (ns < 3)
    throw FitError(file, 0,
                   fmt::format("too few stimuli: {} distinct stimul{}; a fit of slope and intercept needs at least 3 "
                               "(residual degrees of freedom = stimuli - 2 >= 1)",
                               ns, ns == 1 ? "us" : "i"));
  std::set<double> force_levels;
  for (const auto& s : f.stimuli) force_levels.insert(s.x);
  if (force_levels.size() < 2)
    throw FitError(file, 0,
                   fmt::format("only one {0} level ({1:g}{2}) across the {3} stimuli: the slope of the percept on {0} "
                               "needs stimuli at two or more levels",
                               what, f.stimuli.front().x, unit, ns));

  std::vector<double> log_force(ns), log_period(ns), log_mean_r(ns);
  for (std::size_t i = 0; i < ns; ++i) {
    auto& s = f.stimuli[i];
    const double lm = stim_sum[i] / s.estimates;
    s.mean_response = std::pow(10.0, lm);
    log_force[i] = std::log10(s.x);
    log_period[i] = s.period_m > 0 ? std::log10(s.period_m * 1e3) : 0.0;
    log_mean_r[i] = lm;
  }
  // Means that do not vary leave a slope of rounding noise, which a map cannot hold (the loader
  // refuses a zero slope): every estimate the same, or normalised to the same (F32).
  if (varies_too_little(log_mean_r))
    throw FitError(file, 0,
                   fmt::format("every stimulus has the same mean estimate ({:.6g}): there is nothing for {} to "
                               "explain; check the response column",
                               std::pow(10.0, log_mean_r.front()), what));
  const std::string slope_name = f.slope_name();
  f.force = least_squares({slope_name}, {log_force}, log_mean_r, Constant::Fitted);
  if (!(f.force.ss_residual > 1e-20 * f.force.ss_total))
    throw FitError(file, 0,
                   "the mean estimates lie exactly on a line (residual sum of squares 0): no residual is left to estimate "
                   "standard errors from; real estimates scatter, so check the data were not made by a formula");

  // Figure 20: log period beside log force, when the data can say anything about period.
  std::set<double> period_levels;
  for (const auto& s : f.stimuli) period_levels.insert(s.period_m);
  if (period_levels.count(0.0)) {
    f.period_note = "not fitted: the stimuli have no spatial period";
  } else if (period_levels.size() < 2) {
    f.period_note = fmt::format("not fitted: every stimulus has the same period ({:g} mm)", f.stimuli.front().period_m * 1e3);
  } else if (ns < 4) {
    f.period_note = "not fitted: force, period and a constant need at least 4 stimuli";
  } else {
    try {
      f.force_period = least_squares({slope_name, "log period"}, {log_force, log_period}, log_mean_r, Constant::Fitted);
      f.force_period_origin =
          least_squares({slope_name, "log period"}, {log_force, log_period}, log_mean_r, Constant::ThroughOrigin);
    } catch (const std::invalid_argument&) {
      f.force_period.reset();
      f.force_period_origin.reset();
      f.period_note = "not fitted: log period is collinear with log " + what + " over these stimuli";
    }
  }

  // Each subject's own slope, from their per-stimulus geometric means (normalisation does not
  // change a slope).
  std::vector<double> slopes;
  for (std::size_t j = 0; j < f.subjects.size(); ++j) {
    std::vector<double> x, y;
    std::set<double> levels;
    for (std::size_t i = 0; i < ns; ++i)
      if (subj_stim_n[j][i] > 0) {
        x.push_back(log_force[i]);
        y.push_back(subj_stim_sum[j][i] / subj_stim_n[j][i]);
        levels.insert(log_force[i]);
      }
    if (x.size() < 3 || levels.size() < 2) continue;
    try {
      f.subjects[j].slope = least_squares({slope_name}, {x}, y, Constant::Fitted).coefficient(slope_name).value;
      slopes.push_back(*f.subjects[j].slope);
    } catch (const std::invalid_argument&) {
    }
  }
  f.between.subjects = static_cast<int>(slopes.size());
  if (!slopes.empty()) {
    double m = 0;
    for (double v : slopes) m += v;
    m /= static_cast<double>(slopes.size());
    f.between.slope_mean = m;
    if (slopes.size() >= 2) {
      double ss = 0;
      for (double v : slopes) ss += (v - m) * (v - m);
      f.between.slope_sd = std::sqrt(ss / static_cast<double>(slopes.size() - 1));
      f.between.slope_se = f.between.slope_sd / std::sqrt(static_cast<double>(slopes.size()));
    }
  }
  return f;
}

}  // namespace sandpaper::calibration
