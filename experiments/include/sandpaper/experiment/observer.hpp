#pragma once
// Who answers: a person at the terminal, or a simulated observer (docs/EXPERIMENTS.md, "Simulated
// observer") that lets the whole loop, design to installed map, be tested without people.
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "sandpaper/experiment/schedule.hpp"

namespace sandpaper::experiment {

// What was just presented, per stimulus in presentation order. Forces N, periods m.
struct Presented {
  std::vector<std::string> names;
  std::vector<double> felt_force_N;      // measured from the running loop
  std::vector<double> compiled_force_N;
  std::vector<double> period_m;
  std::string percept = "roughness";  // what the subject is asked about (the design's percept)
};

class Observer {
 public:
  virtual ~Observer() = default;
  virtual std::string describe() const = 0;
  virtual void instructions(const std::string& /*title*/, const std::string& /*text*/) {}
  virtual void rest(int /*done*/, int /*total*/) {}
  // Called before each trial's stimuli play (the terminal says what comes).
  virtual void announce(const Trial& /*t*/, int /*total*/) {}
  // Magnitude estimate (> 0) or confidence (0-100 %) of the one presented stimulus; nullopt: the
  // subject stopped the session (it can be resumed).
  virtual std::optional<double> estimate(const Trial& t, const Presented& p, bool confidence) = 0;
  // Two-interval: 1 or 2, the interval that felt stronger; nullopt: stopped.
  virtual std::optional<int> choose_interval(const Trial& t, const Presented& p) = 0;
  // Sorting: for each presented stimulus, its pile (0 .. piles-1); nullopt: stopped.
  virtual std::optional<std::vector<int>> sort(const Trial& t, const Presented& p, int piles) = 0;
  // The session is over: every trial answered (`finished`), or stopped or interrupted.
  virtual void ended(bool /*finished*/) {}
};

// Parameters of `--observer simulated:exponent=0.76,noise=0.15,seed=3` (names as in the spec; every
// one optional):
//   dimension the percept it judges (roughness, softness, viscosity, slipperiness); must be the
//             design's                                                      the design's percept
//   exponent  Stevens exponent of the percept on the felt force (magnitude estimates); negative
//             for softness and slipperiness            the slope of the percept's compile map
//   noise     sd of the natural log of each estimate (log-normal noise); also the sd of the
//             feature noise when sorting and of the confidence, as a fraction of 100 %     0.15
//   modulus   geometric mean of the subjects' moduli (each subject draws its own)           10
//   weber     two-interval: the force increment answered correctly 75 % of the time          0.1
//   period_weight  sorting: weight of log period beside log force in the feature space      0.5
//   seed      random seed (mixed with the subject's id)                                      0
struct SimulatedObserverSpec {
  std::optional<double> exponent;  // nullopt: the caller fills in the percept's compile-map slope
  std::string dimension;           // empty: the design's percept
  double noise = 0.15, modulus = 10, weber = 0.1, period_weight = 0.5;
  std::uint64_t seed = 0;
  std::string text;  // as given
};
// Throws std::invalid_argument naming the bad part ("unknown parameter `x`", "exponent must be > 0").
SimulatedObserverSpec parse_simulated_observer(const std::string& spec);

std::unique_ptr<Observer> make_simulated_observer(const SimulatedObserverSpec& spec, const std::string& subject);
// A person answering at a terminal: prompts on `out`, answers read a line at a time from `in`
// ('q' or end of input stops the session).
std::unique_ptr<Observer> make_terminal_observer(std::istream& in, std::ostream& out);

}  // namespace sandpaper::experiment
