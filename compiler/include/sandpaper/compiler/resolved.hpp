#pragma once
// Phase 3 output: a material with every layer resolved (representative -> perceptual ->
// physical, thesis 1.5.2) into physical parameters in SI, each remembering where it came from.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sandpaper/compiler/source.hpp"

namespace sandpaper::compiler {

enum class Layer { Representative, Perceptual, Physical, Default };
const char* layer_name(Layer l);

// One resolved number: SI value plus provenance.
struct Param {
  double si = 0;
  std::string stated;        // "3.2 mm", "roughness 0.55", "default"
  Layer layer = Layer::Default;
  std::string source;        // "examples/corduroy.hmat:5:3" or "library corduroy (library/corduroy.hmat:7:3)"
  SourceLocation location;   // in the file that said it (empty for defaults)
};

struct ResolvedGrating {
  Param period;       // m
  Param hill;         // fraction of the period that is hill, 0 < hill < 1
  Param orientation;  // rad; 0 = ribs across x (force along x)
  std::optional<Param> smoothing;  // Gaussian sigma, m; default: the thesis' version-2 recipe
  SourceLocation location;         // the grating statement, for diagnostics
};

struct ResolvedHeightmap {
  std::string path;          // file to read (resolved against the material file's folder)
  std::string stated_path;   // as written
  Param width, height;       // m
  std::optional<Param> smoothing;  // Gaussian sigma, m
  std::optional<Param> sampling;   // resampling spacing, m; none: one sample per pixel
  // Stylus reading (thesis 3.4, F = m g tan(theta)): the image's height range is `depth` m of relief
  // and `press` N presses down, so F = -press grad h. Both or neither; then no target force.
  std::optional<Param> depth, press;
  std::string channel;       // channel name; empty: the luminance rule (docs/TEXTURES.md)
  bool repeat = false;
  bool invert = false;       // dark = high
  std::string source;
  SourceLocation location;   // the path in the heightmap statement
  bool stylus() const { return depth && press; }
};

// One `force` or `physics` statement with every parameter resolved (defaults filled in from
// schema/force_laws.hpp), in the law's declared parameter order.
struct ResolvedLaw {
  bool physics = false;
  std::string name;                                   // "AntiViscous"
  std::vector<std::pair<std::string, Param>> params;  // ("stiffness", 200 N/m), ...
  int axes = 3;                                       // periodic laws: 1 = x, 2 = y, 3 = both
  std::string text;                                   // the statement as written
  SourceLocation location;                            // the law's name
  const Param* find(const std::string& param) const {
    for (const auto& [n, p] : params)
      if (n == param) return &p;
    return nullptr;
  }
};

struct ResolvedMaterial {
  std::string name;
  std::string describes;
  std::vector<std::string> like_chain;  // library entries, nearest first
  std::variant<std::monostate, ResolvedGrating, ResolvedHeightmap> texture;
  std::optional<Param> max_lateral_force;  // N: the texture's target maximum lateral force
  std::optional<Param> roughness;          // the ratio-scale roughness asked for, if any
  std::optional<Param> spring;             // N/m
  std::optional<Param> damper;             // N*s/m
  std::vector<ResolvedLaw> laws;           // force laws and physics models, summed in order
  std::optional<Param> energy_budget;      // J, for non-passive laws
  std::optional<Param> energy_refill;      // W
  Param size_width, size_height;           // m
  bool extrapolate = false;
};

}  // namespace sandpaper::compiler
