#pragma once
// The Weber fractions `library near` counts JNDs in, one per perceptual dimension, and an entry's
// place on the force-law dimensions in those JNDs (docs/LIBRARY.md, "Perceptual distance").
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/calibration/calibration.hpp"

namespace sandpaper::curation {

// The Weber fraction each dimension's differences are counted in (docs/LIBRARY.md, "Perceptual
// distance"): a texture's force in force JNDs (Minsky 1995 5.4.2), a spring's stiffness in the
// softness map's, a damper's damping in the viscosity map's, a friction coefficient in the
// slipperiness map's ([jnd] of calibration/maps/). Each in (0, 1].
struct WeberFractions {
  double force = 0, stiffness = 0, damping = 0, friction = 0;
  WeberFractions() = default;
  // Every dimension in force JNDs (an index without the others, and tests of the force axis).
  WeberFractions(double all) : force(all), stiffness(all), damping(all), friction(all) {}  // NOLINT: implicit on purpose
  // For a term parameter ("spring.stiffness_N_per_m", "friction.kinetic_coefficient"): its
  // dimension's fraction; any other parameter is counted in force JNDs, its force scaling with it.
  double for_term(const std::string& key) const;
  bool valid() const;  // every fraction in (0, 1]
};

// The fractions of a calibration: the force JND's, and each percept's compile map's [jnd]
// (the force JND's where a map gives none).
WeberFractions weber_fractions_of(const calibration::CalibrationSet& cal);

// An entry's place on the law dimensions, in JNDs: ln(x) / ln(1 + w) of the first positive spring
// stiffness, damper damping and friction kinetic coefficient among its term parameters, in that
// order; nullopt for one it lacks. The index's R*Tree `laws` holds them for untextured entries.
std::array<std::optional<double>, 3> law_coordinates(const std::vector<std::pair<std::string, double>>& term_params,
                                                     const WeberFractions& w);

}  // namespace sandpaper::curation
