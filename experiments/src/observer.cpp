// The two observers. The simulated one answers from the force the loop actually produced, so what
// a calibration recovers includes whatever the device and loop did to the force.
#include "sandpaper/experiment/observer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <istream>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>

#include "sandpaper/experiment/clustering.hpp"
#include "sandpaper/experiment/percept_quantity.hpp"

namespace sandpaper::experiment {
namespace {

double number(const std::string& key, const std::string& value) {
  double v = 0;
  const auto* end = value.data() + value.size();
  auto [p, ec] = std::from_chars(value.data(), end, v);
  if (ec != std::errc() || p != end || !std::isfinite(v))
    throw std::invalid_argument("simulated observer: `" + key + "=" + value + "` is not a number");
  return v;
}

class SimulatedObserver final : public Observer {
 public:
  SimulatedObserver(SimulatedObserverSpec spec, const std::string& subject) : spec_(std::move(spec)) {
    rng_.seed(subject_seed(spec_.seed, subject));
    // Free modulus (thesis 5.2.3): every subject picks their own scale.
    modulus_ = spec_.modulus * std::exp(0.5 * gauss());
  }
  std::string describe() const override { return "simulated:" + spec_.text; }

  std::optional<double> estimate(const Trial&, const Presented& p, bool confidence) override {
    const double f = std::max(p.felt_force_N.at(0), 1e-6);
    // Every percept is judged from the force the hand met: the scripted hand's excursion and speed
    // are fixed, so a spring's, a damper's and friction's largest force is proportional to the
    // stiffness, damping or coefficient, and an exponent on the felt force is the exponent on it.
    if (!confidence) return modulus_ * std::pow(f, spec_.exponent.value_or(0.76)) * std::exp(spec_.noise * gauss());
    // Chapter 4's pattern: confidence rises with force and falls for coarse periods (> 9.25 mm,
    // the region calibration/knowledge/believability.toml holds); 50 % at 30 pu = 0.55 N.
    const double period_mm = p.period_m.at(0) * 1e3;
    const double z = 4.0 * std::log10(f / 0.55) - 3.0 * std::max(0.0, std::log10(period_mm / 9.25));
    const double c = 100.0 / (1.0 + std::exp(-z)) + 100.0 * spec_.noise * gauss();
    return std::clamp(std::round(c), 0.0, 100.0);
  }

  std::optional<int> choose_interval(const Trial&, const Presented& p) override {
    // Each interval's log force is perceived with Gaussian noise of sd sigma; with sigma chosen so
    // that an increment of `weber` is answered correctly 75 % of the time:
    // P(correct) = Phi(ln(1 + d) / (sigma sqrt 2)) = 0.75 at d = weber.
    const double z75 = boost::math::quantile(boost::math::normal(), 0.75);
    const double sigma = std::log1p(spec_.weber) / (std::sqrt(2.0) * z75);
    const double a = std::log(std::max(p.felt_force_N.at(0), 1e-9)) + sigma * gauss();
    const double b = std::log(std::max(p.felt_force_N.at(1), 1e-9)) + sigma * gauss();
    return a > b ? 1 : 2;
  }

  std::optional<std::vector<int>> sort(const Trial&, const Presented& p, int piles) override {
    // Similar roughness = near in (log force, period_weight x log period), each sort with fresh
    // perceptual noise; piles are the clusters of an average-linkage tree cut at `piles`.
    const std::size_t n = p.names.size();
    std::vector<std::vector<double>> d(n, std::vector<double>(n, 0));
    std::vector<std::pair<double, double>> x(n);
    for (std::size_t i = 0; i < n; ++i)
      x[i] = {std::log10(std::max(p.felt_force_N[i], 1e-9)) + spec_.noise * gauss(),
              spec_.period_weight * std::log10(std::max(p.period_m[i], 1e-6)) + spec_.noise * gauss()};
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) d[i][j] = std::hypot(x[i].first - x[j].first, x[i].second - x[j].second);
    const auto tree = cluster(d, Linkage::Average);
    return cut_tree(tree, n, piles);
  }

 private:
  double gauss() { return std::normal_distribution<double>(0.0, 1.0)(rng_); }
  SimulatedObserverSpec spec_;
  std::mt19937_64 rng_;
  double modulus_ = 1;
};

class TerminalObserver final : public Observer {
 public:
  TerminalObserver(std::istream& in, std::ostream& out) : in_(in), out_(out) {}
  std::string describe() const override { return "terminal"; }
  void instructions(const std::string& title, const std::string& text) override {
    out_ << "\n" << title << "\n\n";
    for (const auto& p : instruction_paragraphs(text)) out_ << p << "\n\n";
    out_ << "Press Enter to begin. " << std::flush;
    std::string line;
    std::getline(in_, line);
  }
  void rest(int done, int total) override {
    out_ << fmt::format("\nTime for a rest: {} of {} trials done. Press Enter when you are ready. ", done, total)
         << std::flush;
    std::string line;
    std::getline(in_, line);
  }
  void announce(const Trial& t, int total) override {
    out_ << fmt::format("\n{} {} of {}: feel the surface{}...\n", t.practice ? "Practice trial" : "Trial", t.index + 1,
                        total, t.stimuli.size() > 1 ? "s" : "")
         << std::flush;
  }
  std::optional<double> estimate(const Trial&, const Presented& presented, bool confidence) override {
    const auto* q = find_percept_quantity(presented.percept);
    for (;;) {
      if (confidence) out_ << "How confident are you that this is a textured surface (0-100 %)? ";
      else if (q) out_ << q->question << " (any positive number; " << q->more << ")? ";
      else out_ << "How rough was it (any positive number; larger = rougher)? ";
      out_ << std::flush;
      auto line = read_line();
      if (!line) return std::nullopt;
      double v = 0;
      auto [p, ec] = std::from_chars(line->data(), line->data() + line->size(), v);
      const bool ok = ec == std::errc() && p == line->data() + line->size() && std::isfinite(v) &&
                      (confidence ? v >= 0 && v <= 100 : v > 0);
      if (ok) return v;
      out_ << (confidence ? "Please type a number from 0 to 100, or q to stop.\n"
                          : "Please type a positive number, or q to stop.\n");
    }
  }
  std::optional<int> choose_interval(const Trial&, const Presented&) override {
    for (;;) {
      out_ << "Which felt stronger, the first or the second (1 or 2)? " << std::flush;
      auto line = read_line();
      if (!line) return std::nullopt;
      if (*line == "1" || *line == "2") return (*line)[0] - '0';
      out_ << "Please type 1 or 2, or q to stop.\n";
    }
  }
  std::optional<std::vector<int>> sort(const Trial&, const Presented& p, int piles) override {
    for (;;) {
      out_ << fmt::format("Sort patches 1-{} into {} piles of similar roughness: type each patch's pile (1-{}) "
                          "in patch order, separated by spaces: ",
                          p.names.size(), piles, piles)
           << std::flush;
      auto line = read_line();
      if (!line) return std::nullopt;
      std::istringstream is(*line);
      std::vector<int> out;
      int k = 0;
      while (is >> k) out.push_back(k - 1);
      bool ok = out.size() == p.names.size() && is.eof();
      for (int v : out) ok = ok && v >= 0 && v < piles;
      for (int pile = 0; ok && pile < piles; ++pile) ok = std::count(out.begin(), out.end(), pile) > 0;
      if (ok) return out;
      out_ << fmt::format("Please give {} numbers from 1 to {}, using every pile, or q to stop.\n", p.names.size(), piles);
    }
  }

 private:
  std::optional<std::string> read_line() {
    std::string line;
    if (!std::getline(in_, line)) return std::nullopt;
    line.erase(0, line.find_first_not_of(" \t\r"));
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line == "q" || line == "quit") return std::nullopt;
    return line;
  }
  std::istream& in_;
  std::ostream& out_;
};

}  // namespace

SimulatedObserverSpec parse_simulated_observer(const std::string& spec) {
  SimulatedObserverSpec s;
  std::string rest = spec;
  if (rest.rfind("simulated", 0) != 0)
    throw std::invalid_argument("observer `" + spec + "`: give `terminal` or `simulated:exponent=0.76,noise=0.15,seed=3`");
  rest.erase(0, 9);
  if (!rest.empty() && rest[0] == ':') rest.erase(0, 1);
  else if (!rest.empty()) throw std::invalid_argument("observer `" + spec + "`: parameters follow `simulated:`");
  s.text = rest;
  std::istringstream is(rest);
  std::string part;
  while (std::getline(is, part, ',')) {
    if (part.empty()) continue;
    const auto eq = part.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("simulated observer: `" + part + "` is not name=value");
    const std::string key = part.substr(0, eq), value = part.substr(eq + 1);
    if (key == "seed") {
      std::uint64_t v = 0;
      auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
      if (ec != std::errc() || p != value.data() + value.size())
        throw std::invalid_argument("simulated observer: seed must be a whole number >= 0");
      s.seed = v;
    } else if (key == "exponent") s.exponent = number(key, value);
    else if (key == "dimension") {
      if (!find_percept_quantity(value))
        throw std::invalid_argument("simulated observer: dimension `" + value + "` is not one of " + percept_quantity_names());
      s.dimension = value;
    }
    else if (key == "noise") s.noise = number(key, value);
    else if (key == "modulus") s.modulus = number(key, value);
    else if (key == "weber") s.weber = number(key, value);
    else if (key == "period_weight") s.period_weight = number(key, value);
    else
      throw std::invalid_argument("simulated observer: unknown parameter `" + key +
                                  "` (known: dimension, exponent, noise, modulus, weber, period_weight, seed)");
  }
  if (s.exponent && !(*s.exponent != 0))
    throw std::invalid_argument("simulated observer: exponent must not be 0 (negative for a percept that falls as its "
                                "quantity grows, e.g. softness)");
  if (!(s.noise >= 0)) throw std::invalid_argument("simulated observer: noise must be >= 0");
  if (!(s.modulus > 0)) throw std::invalid_argument("simulated observer: modulus must be > 0");
  if (!(s.weber > 0)) throw std::invalid_argument("simulated observer: weber must be > 0");
  if (!(s.period_weight >= 0)) throw std::invalid_argument("simulated observer: period_weight must be >= 0");
  return s;
}

std::unique_ptr<Observer> make_simulated_observer(const SimulatedObserverSpec& spec, const std::string& subject) {
  return std::make_unique<SimulatedObserver>(spec, subject);
}

std::unique_ptr<Observer> make_terminal_observer(std::istream& in, std::ostream& out) {
  return std::make_unique<TerminalObserver>(in, out);
}

}  // namespace sandpaper::experiment
