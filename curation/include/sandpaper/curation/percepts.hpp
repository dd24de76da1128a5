#pragma once
// An entry's perceptual coordinates and physical summary, read off its compiled program: what the
// index stores, what `near` measures and what the JND-collision check compares.
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/compiler/recovered_height_field.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::curation {

struct Percepts {
  double roughness = 0;            // ratio scale (calibrated map); 0 when there is no texture
  double max_lateral_force_N = 0;  // the texture's; 0 when there is none
  std::string texture_kind;        // "grating", "grid", "perlin", "image", "noise", "stripes"; empty: no texture
  double period_m = 0;             // spatial period or feature size, or an image's spatial_scale_m; 0 when the kind has none
  std::string period_class;        // Minsky 1995 6.3.6 class id ("textural", "transitional", "features"); empty without a period
  std::string character;           // 6.3.7 group id (gratings only), e.g. "moguls"; empty otherwise
  std::string terms;               // the program's term kinds in order, '+'-joined: "grating+spring"
  // Other perceptual targets the material asked for: (percept, ratio-scale value), e.g. ("viscosity", 0.4).
  std::vector<std::pair<std::string, double>> others;
  // The non-texture terms' scalar parameters, "<term kind>.<field with unit>": ("damper.damping_Ns_per_m", -2).
  std::vector<std::pair<std::string, double>> term_params;
  bool has_texture() const { return max_lateral_force_N > 0; }
};

Percepts percepts_of(const compiler::ResolvedMaterial& m, const schema::PatchProgram& p,
                     const calibration::CalibrationSet& cal);

// A texture's spatial scale, m: four times the lag at which the autocorrelation of its heights
// (compiler::recover_height_field, mean removed) first falls to zero, along x or along y, whichever is
// shorter: a sinusoid of period P across that axis gives P (its autocorrelation is cos(2 pi d / P)).
// Proportional to an image's size on the patch. 0 for a flat field, or one that does not
// decorrelate within half its width.
double spatial_scale_m(const compiler::RecoveredHeightField& heights);

// One line, units explicit: "grating period 3.2 mm, hill 60 %; maximum lateral force 1.23 N; spring 200 N/m".
std::string physical_summary(const compiler::ResolvedMaterial& m, const schema::PatchProgram& p);

// Two textured entries the thesis' knowledge cannot tell apart (the W0601 rule, docs/LIBRARY.md):
// same texture kind and term kinds, maximum lateral forces less than one force JND apart
// (calibration/knowledge/force-jnd.toml, Minsky 1995 5.4.2), and the same 6.3.6 period class
// (kinds without a period, and image textures: never, their pictures differ). `steps` gets the JND steps between them.
bool indistinguishable(const Percepts& a, const Percepts& b, const calibration::ForceJndData& jnd, double* steps = nullptr);

}  // namespace sandpaper::curation
