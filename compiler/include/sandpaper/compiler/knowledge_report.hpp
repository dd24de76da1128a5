#pragma once
// What the thesis' qualitative knowledge (calibration/knowledge/) says about one compiled material:
// whether it lies in Ch. 4's believable region, its 6.3.6 period class and 6.3.7 group, a
// non-textural stimulus's mean confidence (Table 4), and how many force JNDs separate it from the
// named roughness levels either side (5.4.2). `sandpaper explain` prints it; W0330 comes from it.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// The texture's kind and spatial period as the thesis' experiments describe them: "grating"
// (version-2 `grating` and `pattern bars`: period = hill + valley), "grid" (`pattern grid`),
// "perlin" (`pattern perlin`: feature size); anything else has no period here.
struct TextureGeometry {
  std::string kind;            // "grating", "grid", "perlin", "image", "noise", "stripes"; empty: no texture
  double period_m = 0;         // spatial period or feature size; 0 when the kind has none
  bool has_period() const { return period_m > 0; }
};
TextureGeometry texture_geometry(const ResolvedMaterial& m);

// One named roughness level near the material, and the force JNDs from the material to it (signed:
// positive when the level is stronger).
struct LevelNeighbour {
  const calibration::Level* level = nullptr;
  double force_N = 0;
  double jnd_steps = 0;
};

struct GroupPlacement {
  const calibration::Grouping* grouping = nullptr;
  calibration::Grouping::Hit hit;
  bool in_domain = false;                          // inside Table 8's measured forces and periods
  const calibration::MeasuredStimulus* nearest = nullptr;
};

struct KnowledgeReport {
  TextureGeometry texture;
  double force_N = 0;                              // the texture's maximum lateral force; 0 without one
  // Ch. 4: set for kinds with a low-confidence region (grating, grid, perlin).
  const calibration::LowConfidenceRegion* region = nullptr;
  bool believable = true;                          // false: inside `region`
  // 6.3.6 and 6.3.7: period class for textures with a period; group for gratings only.
  std::optional<GroupPlacement> period_class, character;
  // Ch. 4 Table 4: the thesis non-textural this material is (by law or by stimulus name).
  const calibration::NonTexturalConfidence* non_textural = nullptr;
  // 5.4.2: named roughness levels around the force. `at` when the force is a named level's (within
  // 1e-6); `below` / `above` the nearest levels under and over it (or either side of `at`).
  std::optional<LevelNeighbour> at, below, above;
};

KnowledgeReport assess_knowledge(const ResolvedMaterial& m, const schema::PatchProgram& p,
                                 const calibration::CalibrationSet& cal);

// The "knowledge" and "maps" sections of `sandpaper explain`, as text (each line indented by two
// spaces, no heading) and as JSON (keys documented in docs/CALIBRATION.md, "Knowledge").
std::string knowledge_text(const KnowledgeReport& k, const calibration::CalibrationSet& cal);
std::string maps_text(const calibration::CalibrationSet& cal);
nlohmann::json knowledge_json(const KnowledgeReport& k, const calibration::CalibrationSet& cal);
nlohmann::json maps_json(const calibration::CalibrationSet& cal);

// W0330: a grating or grid inside Ch. 4's low-confidence region (calibration/knowledge/believability.toml).
void warn_believability(const ResolvedMaterial& m, const schema::PatchProgram& p, const calibration::CalibrationSet& cal,
                        Diagnostics& diags);

// "12.5 % of force (tan1992: Tan 1992 ... ; calibration/knowledge/force-jnd.toml)": the JND the
// compiler counts with and where it comes from, for messages.
std::string jnd_source(const calibration::ForceJndData& jnd);

}  // namespace sandpaper::compiler
