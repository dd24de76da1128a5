#include "sandpaper/experiment/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "sandpaper/calibration/fit_json.hpp"
#include "sandpaper/calibration/regression.hpp"
#include "sandpaper/experiment/clustering.hpp"
#include "sandpaper/experiment/percept_quantity.hpp"
#include "sandpaper/experiment/plots.hpp"
#include "sandpaper/experiment/psychometric.hpp"
#include "sandpaper/schema/atomic_file.hpp"

namespace sandpaper::experiment {
namespace {

using nlohmann::json;

void write_picture(Analysis& a, const std::filesystem::path& dir, const std::string& name, const std::string& svg) {
  std::filesystem::create_directories(dir);
  schema::write_file_atomically(dir / name, svg);
  a.pictures.push_back(dir / name);
}

// The design's practice trials (its `practice`), read from the run's copy of the design.
int practice_trials(const Results& r) {
  try {
    const auto doc = toml::parse(r.design_text);
    return static_cast<int>(doc["practice"].value_or(std::int64_t{0}));
  } catch (const toml::parse_error&) {
    return 0;  // read_results checked the copy's checksum; a copy that does not parse has no practice to count
  }
}

std::vector<const Answer*> analysed(const Analysis& a) {
  std::vector<const Answer*> out;
  for (const auto& r : a.runs)
    for (const auto& ans : r.answers)
      if (!ans.practice) out.push_back(&ans);
  return out;
}

json magnitude(Analysis& a, const std::filesystem::path& pictures) {
  calibration::MagnitudeEstimationData data;
  data.path = a.runs.size() == 1 ? a.runs.front().dir.string() : a.runs.front().dir.parent_path().string();
  const std::string& percept = a.runs.front().header.percept;
  for (const auto& r : a.runs)
    if (r.header.percept != percept)
      throw DesignError(fmt::format("error: {} scaled {} but {} scaled {}; a fit is of one percept", a.runs.front().dir.string(),
                                    percept, r.dir.string(), r.header.percept));
  const PerceptQuantity* q = find_percept_quantity(percept);
  if (!q) throw DesignError("error: results of percept `" + percept + "`, which no analysis knows (" + percept_quantity_names() + ")");
  const bool roughness = percept == "roughness";
  data.predictor = fit_predictor(*q);
  const auto x_of = [&](const Answer& ans) { return roughness ? ans.compiled_force_N.at(0) : ans.quantity.at(0); };
  for (const auto& r : a.runs)
    for (const auto& ans : r.answers) {
      if (ans.practice) continue;
      calibration::Trial t;
      t.subject = r.header.subject;
      t.stimulus = ans.stimuli.at(0);
      // The map inverts the compiled number (what `compile --device` will ask the device for), so the
      // regression is on the compiled force (or stiffness, ...); the felt force is reported beside it.
      if (!roughness && ans.quantity.empty())
        throw DesignError(r.dir.string() + ": error: trial " + std::to_string(ans.trial + 1) + " records no " + q->results_key);
      t.x = x_of(ans);
      t.period_m = ans.period_m.at(0);
      t.response = ans.response;
      data.trials.push_back(std::move(t));
    }
  a.magnitude = calibration::fit_magnitude_estimation(data);
  const auto& fit = *a.magnitude;
  json j = calibration::fit_json(fit);
  j["n_trials"] = fit.answered;
  // Felt against compiled force: how faithfully the device produced what was asked.
  // A stimulus that compiles no texture force (a damper, a spring) has nothing to compare: then the
  // difference is null and `felt_vs_compiled` says "not compared", never a reassuring 0.
  double worst = 0;
  int compared = 0;
  for (const auto* ans : analysed(a)) {
    const double c = ans->compiled_force_N.at(0), f = ans->felt_force_N.at(0);
    if (c > 0) {
      worst = std::max(worst, std::abs(f / c - 1));
      ++compared;
    }
  }
  j["felt_vs_compiled_max_rel_diff"] = compared > 0 ? json(worst) : json(nullptr);
  j["felt_vs_compiled_trials"] = compared;
  j["felt_vs_compiled"] = compared > 0 ? fmt::format("compared on {} trials", compared)
                                       : std::string("not compared: no trial's stimulus compiles a force to compare "
                                                     "the felt force with");
  // The per-trial normalised estimates for the picture (each subject's / their geometric mean x the grand one).
  std::map<std::string, double> gm;
  for (const auto& s : fit.subjects) gm[s.subject] = s.geometric_mean;
  std::vector<EstimatePoint> points;
  for (const auto& r : a.runs)
    for (const auto& ans : r.answers)
      if (!ans.practice && ans.response && gm[r.header.subject] > 0)
        points.push_back({x_of(ans), *ans.response / gm[r.header.subject] * fit.grand_geometric_mean});
  const std::string title = fmt::format("Magnitude estimation of {}: {} subjects, {} stimuli", percept, fit.subjects.size(),
                                        fit.stimuli.size());
  j["percept"] = percept;
  write_picture(a, pictures, "magnitude-estimation.svg", magnitude_plot_svg(fit, points, title));
  j["plot"] = (pictures / "magnitude-estimation.svg").string();
  return j;
}

json confidence(Analysis& a) {
  struct Acc {
    double force = 0, period = 0, sum = 0, sum2 = 0;
    int n = 0;
  };
  std::map<std::string, Acc> per;
  std::vector<std::string> order;
  for (const auto* ans : analysed(a)) {
    if (!ans->response) continue;
    auto [it, fresh] = per.try_emplace(ans->stimuli.at(0));
    if (fresh) order.push_back(ans->stimuli.at(0));
    it->second.force = ans->compiled_force_N.at(0);
    it->second.period = ans->period_m.at(0);
    it->second.sum += *ans->response;
    it->second.sum2 += *ans->response * *ans->response;
    ++it->second.n;
  }
  json stimuli = json::array();
  std::vector<double> lf, lp, logit;
  for (const auto& name : order) {
    const auto& s = per[name];
    const double mean = s.sum / s.n;
    const double sd = s.n > 1 ? std::sqrt(std::max(0.0, (s.sum2 - s.n * mean * mean) / (s.n - 1))) : 0.0;
    stimuli.push_back({{"stimulus", name}, {"force_N", s.force}, {"period_mm", s.period * 1e3}, {"n", s.n},
                       {"mean_confidence", mean}, {"sd", sd}});
    if (s.force > 0 && s.period > 0) {
      const double p = std::clamp(mean / 100.0, 0.01, 0.99);
      lf.push_back(std::log10(s.force));
      lp.push_back(std::log10(s.period * 1e3));
      logit.push_back(std::log(p / (1 - p)));
    }
  }
  json j{{"stimuli", stimuli}};
  // The 50 % boundary: logit(mean/100) = b0 + b1 log10 F + b2 log10 period(mm) = 0.
  try {
    const auto r = calibration::least_squares({"log force", "log period"}, {lf, lp}, logit, calibration::Constant::Fitted);
    const double b0 = r.coefficient("constant").value, b1 = r.coefficient("log force").value,
                 b2 = r.coefficient("log period").value;
    json at = json::array();
    for (double mm : {1.0, 2.5, 5.0, 10.0})
      at.push_back({{"period_mm", mm},
                    {"force_N", b1 != 0 ? json(std::pow(10.0, -(b0 + b2 * std::log10(mm)) / b1)) : json(nullptr)}});
    j["boundary"] = {{"model", "logit(mean confidence) = b0 + b1 log10(F / 1 N) + b2 log10(period / 1 mm)"},
                     {"regression", calibration::regression_json(r)},
                     {"force_at_50_percent", at}};
  } catch (const std::invalid_argument& e) {
    j["boundary"] = {{"fitted", false}, {"reason", e.what()}};
  }
  return j;
}

json sorting(Analysis& a, const std::filesystem::path& pictures) {
  std::vector<std::string> names;
  std::map<std::string, std::size_t> index;
  for (const auto* ans : analysed(a))
    for (const auto& pile : ans->piles)
      for (const auto& s : pile)
        if (index.emplace(s, names.size()).second) names.push_back(s);
  std::sort(names.begin(), names.end());
  for (std::size_t i = 0; i < names.size(); ++i) index[names[i]] = i;
  const std::size_t n = names.size();
  std::vector<std::vector<double>> together(n, std::vector<double>(n, 0));
  int sorts = 0;
  for (const auto* ans : analysed(a)) {
    if (ans->piles.empty()) continue;
    ++sorts;
    for (const auto& pile : ans->piles)
      for (const auto& x : pile)
        for (const auto& y : pile) together[index[x]][index[y]] += 1;
  }
  if (n < 3 || sorts == 0) throw DesignError("sorting analysis: fewer than 3 stimuli or no sorts recorded");
  // Distance = sorts in which the two were apart (the thesis' similarity turned into a distance).
  std::vector<std::vector<double>> distance(n, std::vector<double>(n, 0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) distance[i][j] = i == j ? 0 : sorts - together[i][j];
  json j{{"stimuli", names}, {"sorts", sorts}, {"co_occurrence", together}};
  for (auto [linkage, key] : {std::pair{Linkage::Single, "single"}, std::pair{Linkage::Average, "average"}}) {
    const auto merges = cluster(distance, linkage);
    const auto top = cut_tree(merges, n, 2);
    json clusters = json::array({json::array(), json::array()});
    for (std::size_t i = 0; i < n; ++i) clusters[static_cast<std::size_t>(top[i])].push_back(names[i]);
    json tree = json::array();
    for (const auto& m : merges) tree.push_back({{"a", m.a}, {"b", m.b}, {"height", m.height}, {"size", m.size}});
    const std::string file = std::string("dendrogram-") + key + ".svg";
    write_picture(a, pictures, file,
                  dendrogram_svg(names, merges, fmt::format("Sorting: {}-linkage clustering of {} sorts", key, sorts),
                                 "sorts in which the two were apart"));
    j[key] = {{"clusters", clusters}, {"merges", tree}, {"dendrogram", (pictures / file).string()}};
  }
  // The contract's top-level names are the thesis' own analysis, single linkage (6.3).
  j["clusters"] = j["single"]["clusters"];
  j["dendrogram"] = j["single"]["dendrogram"];
  return j;
}

json two_interval(Analysis& a, const std::filesystem::path& pictures) {
  std::map<double, IncrementCount> by;
  for (const auto* ans : analysed(a)) {
    if (!ans->comparison_interval) continue;
    auto& c = by[ans->increment];
    c.increment = ans->increment;
    ++c.trials;
    if (ans->correct) ++c.correct;
  }
  std::vector<IncrementCount> data;
  std::vector<ProportionPoint> points;
  json per = json::array();
  for (const auto& [inc, c] : by) {
    data.push_back(c);
    points.push_back({inc, static_cast<double>(c.correct) / c.trials, c.trials});
    per.push_back({{"increment", inc}, {"trials", c.trials}, {"correct", c.correct}});
  }
  PsychometricFit fit;
  try {
    fit = fit_two_interval(data);
  } catch (const std::invalid_argument& e) {
    throw DesignError(std::string("two-interval analysis: ") + e.what());
  }
  write_picture(a, pictures, "psychometric.svg",
                psychometric_svg(fit, points, "Two-interval forced choice: proportion correct against force increment"));
  auto finite = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return {{"weber_fraction", fit.weber_fraction},
          {"weber_fraction_interval", {finite(fit.weber_low), finite(fit.weber_high)}},
          {"confidence_level", 0.95},
          {"definition", "force increment answered correctly 75 % of the time"},
          {"sigma", fit.sigma},
          {"model", "P(correct) = Phi(ln(1 + increment) / (sigma sqrt 2)), maximum likelihood; interval by likelihood ratio"},
          {"trials", fit.trials},
          {"increments", per},
          {"plot", (pictures / "psychometric.svg").string()}};
}

}  // namespace

std::vector<std::filesystem::path> find_results(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  if (std::filesystem::is_regular_file(dir / "results.jsonl", ec)) out.push_back(dir);
  if (std::filesystem::is_directory(dir, ec))
    for (auto it = std::filesystem::recursive_directory_iterator(dir, ec); it != std::filesystem::recursive_directory_iterator();
         it.increment(ec)) {
      if (ec) break;
      if (it->is_directory() && it->path() != dir && std::filesystem::is_regular_file(it->path() / "results.jsonl", ec))
        out.push_back(it->path());
    }
  std::sort(out.begin(), out.end());
  return out;
}

Analysis analyse(const std::filesystem::path& dir, const AnalyseOptions& options) {
  Analysis a;
  const auto folders = find_results(dir);
  if (folders.empty())
    throw DesignError(dir.string() + ": error: no results here (a results folder holds results.jsonl, written by "
                      "`sandpaper experiment run`)");
  for (const auto& f : folders) a.runs.push_back(read_results(f));
  std::map<std::string, std::vector<std::string>> by_design, by_task;
  for (const auto& r : a.runs) {
    by_design[r.header.design_checksum].push_back(r.dir.string());
    by_task[r.header.task].push_back(r.dir.string());
  }
  auto listing = [](const std::map<std::string, std::vector<std::string>>& m) {
    std::string out;
    for (const auto& [k, v] : m) out += fmt::format("  {}: {}\n", k, fmt::join(v, ", "));
    return out;
  };
  if (by_task.size() > 1) throw DesignError("error: these results are of different tasks and cannot be pooled:\n" + listing(by_task));
  if (by_design.size() > 1 && !options.allow_mixed_designs)
    throw DesignError("error: these results come from different designs (checksums differ); analyse them separately, "
                      "or pass --allow-mixed-designs:\n" + listing(by_design));
  // Completeness: a subject who stopped early answered fewer recorded trials than the schedule holds.
  // Their estimates are left out of a fit (and so of a map) unless asked for: a free modulus
  // estimated from part of the set is not the subject's modulus over the set.
  json runs = json::array();
  std::vector<Results> kept;
  for (auto& r : a.runs) {
    const int practice = practice_trials(r);
    int answered_practice = 0, answered_recorded = 0;
    for (const auto& ans : r.answers) (ans.practice ? answered_practice : answered_recorded)++;
    const int recorded = std::max(0, r.header.trials - practice);
    const bool complete = r.next_trial() >= r.header.trials;
    const bool included = complete || options.include_incomplete;
    runs.push_back({{"folder", r.dir.string()}, {"subject", r.header.subject}, {"device", r.header.device},
                    {"observer", r.header.observer}, {"trials", r.header.trials}, {"practice_trials", practice},
                    {"recorded_trials", recorded}, {"answered", r.answers.size()},
                    {"answered_practice", answered_practice}, {"answered_recorded", answered_recorded},
                    {"complete", complete}, {"included", included}});
    if (included) kept.push_back(std::move(r));
    else a.left_out.push_back(r.dir);
  }
  if (kept.empty())
    throw DesignError(fmt::format("error: no subject in {} answered every trial, and incomplete subjects are left out of "
                                  "the analysis; finish them with `sandpaper experiment resume`, or pass "
                                  "--include-incomplete to pool them anyway",
                                  dir.string()));
  a.runs = std::move(kept);
  // One subject in two folders (a run copied, or an id reused) would count twice in every mean.
  std::map<std::string, std::vector<std::string>> folders_of;
  for (const auto& r : a.runs) folders_of[r.header.subject].push_back(r.dir.string());
  json warnings = json::array(), duplicates = json::array();
  for (const auto& [subject, where] : folders_of)
    if (where.size() > 1) {
      duplicates.push_back({{"subject", subject}, {"folders", where}});
      warnings.push_back(fmt::format("subject {} is in {} results folders ({}): pooled, their answers count {} times; "
                                     "remove the copies, or give each person their own --subject",
                                     subject, where.size(), fmt::join(where, ", "), where.size()));
    }
  std::set<std::string> subjects;
  int trials = 0, answered = 0, interrupted = 0, answered_practice = 0;
  for (const auto& r : a.runs) {
    for (const auto& ans : r.answers) answered_practice += ans.practice ? 1 : 0;
    subjects.insert(r.header.subject);
    trials += r.header.trials;
    answered += static_cast<int>(r.answers.size());
    interrupted += static_cast<int>(r.interruptions.size());
  }
  a.task = a.runs.front().header.task;
  const auto pictures = options.pictures_dir.empty() ? dir / "analysis" : options.pictures_dir;
  a.report = {{"ok", true},
              {"task", a.task},
              {"design_checksums", [&] {
                 json c = json::array();
                 for (const auto& [k, v] : by_design) c.push_back(k);
                 return c;
               }()},
              {"subjects", subjects.size()},
              {"runs", runs},
              {"trials_scheduled", trials},
              {"records_answered", answered},
              {"practice_answered", answered_practice},
              {"recorded_answered", answered - answered_practice},
              {"include_incomplete", options.include_incomplete},
              {"left_out", [&] {
                 json l = json::array();
                 for (const auto& p : a.left_out) l.push_back(p.string());
                 return l;
               }()},
              {"interruptions", interrupted},
              {"duplicate_subjects", duplicates},
              {"warnings", warnings}};
  if (a.task == "magnitude-estimation") {
    json m = magnitude(a, pictures);
    a.report["magnitude_estimation"] = m;
  } else if (a.task == "confidence") {
    a.report["confidence"] = confidence(a);
  } else if (a.task == "sorting") {
    a.report["sorting"] = sorting(a, pictures);
  } else if (a.task == "two-interval") {
    a.report["two_interval"] = two_interval(a, pictures);
  }
  json pics = json::array();
  for (const auto& p : a.pictures) pics.push_back(p.string());
  a.report["pictures"] = pics;
  return a;
}

}  // namespace sandpaper::experiment
