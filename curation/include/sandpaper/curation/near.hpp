#pragma once
// `sandpaper library near`: the perceptually nearest entries (docs/LIBRARY.md, "Perceptual distance").
#include <string>
#include <vector>

#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/weber_fractions.hpp"

namespace sandpaper::curation {

// Weights of the distance, in force-JND steps (Minsky 1995 5.4.2; 12.5 %, calibration/knowledge/force-jnd.toml).
// Designed, not measured: one doubling of spatial period counts as kJndPerPeriodDoubling steps, a
// different texture kind as kKindSteps, textured against untextured as kTextureSteps.
inline constexpr double kJndPerPeriodDoubling = 4.0;
inline constexpr double kKindSteps = 8.0;
inline constexpr double kTextureSteps = 20.0;

struct Neighbour {
  IndexedEntry entry;
  double distance = 0;      // in force-JND steps
  double force_steps = 0;   // ln(F2/F1) / ln(1 + weber), signed: positive when the neighbour is stronger
  double period_doublings = 0;  // log2(P2/P1), signed; 0 when either has no period
  std::string why;          // "0.8 JND weaker (1.05 vs 1.16 N); period 2.5 vs 3.2 mm (-0.36 doublings); same kind (grating)"
};

// Distance between two indexed entries with Weber fraction `weber` (0.125). `explain` false: the
// numbers only (no `why`, no copy of `to`), for comparing many entries.
Neighbour distance_between(const IndexedEntry& from, const IndexedEntry& to, const WeberFractions& weber, bool explain = true);
// The `limit` nearest entries to `name` (a name; resolve aliases first), nearest first, ties by name;
// of family `family` only, unless it is empty.
std::vector<Neighbour> nearest(const Index& index, const std::string& name, std::size_t limit, const std::string& family = "");
// The same for an entry that may be another index's (a root in front, in a layered path), with
// that index's Weber fraction; an entry of this index with from's name is not a neighbour.
// Throws std::invalid_argument unless every fraction is in (0, 1] (a caller's error).
std::vector<Neighbour> nearest_to(const Index& index, const IndexedEntry& from, std::size_t limit, const WeberFractions& weber,
                                  const std::string& family = "");

}  // namespace sandpaper::curation
