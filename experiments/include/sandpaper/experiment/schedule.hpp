#pragma once
// The order of trials one subject gets: a pure function of the design and the subject's id, so a
// resumed session (and anyone re-analysing it) rebuilds exactly the order that was run. Each
// repetition is its own shuffle of the set (the thesis' runs, 5.2.3), drawn with the project's
// platform-independent Fisher-Yates (compiler/shuffle.hpp, thesis Appendix B's Shuffle).
#include <cstdint>
#include <string>
#include <vector>

#include "sandpaper/experiment/design.hpp"

namespace sandpaper::experiment {

struct Trial {
  int index = 0;               // 0-based position in the session, practice trials first
  bool practice = false;       // practice trials are recorded but never analysed
  int repetition = 0;          // 0-based run through the set (practice: 0)
  std::vector<int> stimuli;    // indices into the design's stimuli, in presentation order
                               // (one for magnitude estimation and confidence, all for sorting,
                               // the standard once for two-interval)
  int piles = 0;               // sorting: how many piles to make
  double increment = 0;        // two-interval: the comparison is the standard x (1 + increment)
  int comparison_interval = 0; // two-interval: 1 or 2, which interval plays the comparison
};

// The seed of one subject's shuffles: the design's seed mixed with the subject's id (FNV-1a), so
// subjects get different orders and the same subject always gets the same one.
std::uint64_t subject_seed(std::uint64_t design_seed, const std::string& subject);

std::vector<Trial> make_schedule(const Design& design, const std::string& subject);

}  // namespace sandpaper::experiment
