#include "sandpaper/experiment/schedule.hpp"

#include <random>

#include "sandpaper/compiler/shuffle.hpp"

namespace sandpaper::experiment {

std::uint64_t subject_seed(std::uint64_t design_seed, const std::string& subject) {
  return design_seed ^ fnv1a64(subject);
}

std::vector<Trial> make_schedule(const Design& design, const std::string& subject) {
  const std::uint64_t seed = subject_seed(design.seed, subject);
  std::mt19937_64 rng(seed);
  const auto n = design.stimuli.size();
  std::vector<Trial> out;
  auto add = [&](Trial t) {
    t.index = static_cast<int>(out.size());
    out.push_back(std::move(t));
  };
  auto all_shuffled = [&]() {
    std::vector<int> order;
    for (auto i : compiler::seeded_permutation(n, rng())) order.push_back(static_cast<int>(i));
    return order;
  };

  // What one run through the set is, per task, before shuffling.
  std::vector<Trial> block;
  switch (design.task) {
    case Task::MagnitudeEstimation:
    case Task::Confidence:
      for (std::size_t i = 0; i < n; ++i) block.push_back(Trial{0, false, 0, {static_cast<int>(i)}, 0, 0, 0});
      break;
    case Task::Sorting:
      // Successive sorts of one set (6.2.5): the pile counts stay in the design's order.
      for (int k : design.piles) block.push_back(Trial{0, false, 0, {}, k, 0, 0});
      break;
    case Task::TwoInterval:
      for (double inc : design.increments) block.push_back(Trial{0, false, 0, {0}, 0, inc, 0});
      break;
  }

  // Practice: trials drawn from the block in a shuffled order (repeating it if practice > block).
  for (int p = 0; p < design.practice; ++p) {
    const auto perm = compiler::seeded_permutation(block.size(), rng());
    Trial t = block[perm[0]];
    t.practice = true;
    if (design.task == Task::Sorting) t.stimuli = all_shuffled();
    if (design.task == Task::TwoInterval) t.comparison_interval = 1 + static_cast<int>(compiler::uniform_below(rng, 2));
    add(std::move(t));
  }
  for (int r = 0; r < design.repetitions; ++r) {
    const bool keep_order = design.task == Task::Sorting;
    const auto perm = compiler::seeded_permutation(block.size(), rng());
    for (std::size_t k = 0; k < block.size(); ++k) {
      Trial t = block[keep_order ? k : perm[k]];
      t.repetition = r;
      // Sorting: the patches get a fresh random numbering each sort, as the thesis' randomly
      // numbered black patches did (6.2.5).
      if (design.task == Task::Sorting) t.stimuli = all_shuffled();
      if (design.task == Task::TwoInterval) t.comparison_interval = 1 + static_cast<int>(compiler::uniform_below(rng, 2));
      add(std::move(t));
    }
  }
  return out;
}

}  // namespace sandpaper::experiment
