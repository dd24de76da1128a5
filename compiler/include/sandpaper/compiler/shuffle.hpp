#pragma once
// Seeded shuffles that come out the same on every platform: Fisher-Yates driven by
// std::mt19937_64, whose output sequence the C++ standard fixes, with each index drawn by
// rejection sampling. (std::shuffle and std::uniform_int_distribution are left to each standard
// library and differ between them.) Used for movie shuffles, thesis Appendix B.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace sandpaper::compiler {

// A uniform integer in [0, bound) from `rng`, without modulo bias: draws below 2^64 mod bound are
// rejected, so the accepted range is a whole number of copies of [0, bound). Throws
// std::invalid_argument for bound 0.
std::uint64_t uniform_below(std::mt19937_64& rng, std::uint64_t bound);

// A permutation of 0 .. n-1: element k of the result is the original position of the item that
// lands at position k. Fisher-Yates from the last position down: position i swaps with a uniform
// j in [0, i]. Seeded with std::mt19937_64(seed).
std::vector<std::size_t> seeded_permutation(std::size_t n, std::uint64_t seed);

}  // namespace sandpaper::compiler
