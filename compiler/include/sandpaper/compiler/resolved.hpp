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

// A version-1 synthetic height map (thesis 3.5.1). Lengths are whole pixels of `pixel`; kernel
// sizes are the Gaussian's sigma in pixels (docs/TEXTURES.md, "Patterns": the reading that gives 3.6.1's counts).
enum class PatternKind { Bars, Grid, Perlin, Noise, Stripes };
const char* pattern_kind_name(PatternKind k);
struct ResolvedPattern {
  PatternKind kind = PatternKind::Bars;
  Param pixel;                             // m, the array's pitch (thesis: 0.37 mm)
  std::optional<Param> valley, hill;       // m, whole pixels (bars, grid)
  std::optional<Param> offset;             // m, whole pixels: alternate rows of grid bumps shift by this
  std::optional<Param> feature;            // m: Perlin lattice size; noise cell size
  std::optional<Param> kernel, refilter;   // px: Gaussian kernel size of the first and of a second pass
  std::optional<Param> seed;               // perlin, noise
  std::optional<Param> count;              // stripes: how many hills
  SourceLocation location;                 // the pattern statement
};

// A perceptual target other than roughness (compiler/percepts.hpp): the ratio-scale value asked
// for, the parameter it set and the map it went through.
struct PerceptTarget {
  std::string word;       // as written: "stickiness"
  std::string percept;    // "viscosity"
  std::string parameter;  // what it set: "damper.damping", "friction.coefficient", "spring.stiffness", "texture.period"
  Param value;            // the ratio-scale number, stated "stickiness 0.4"
  std::string map_id;     // "stevens-guirao1964"
  std::string map_file;   // "calibration/maps/stevens-guirao1964.toml"
  bool provisional = false;  // the map has no published or measured source: every output warns W0320
  bool real_material = false;  // the map's source felt real specimens, not a device: every output warns W0321
};

struct ResolvedMaterial {
  std::string name;
  std::string describes;
  std::vector<std::string> like_chain;  // library entries, nearest first
  // Where each like_chain entry came from: "library/corduroy.hmat", or the thesis stimulus generator.
  std::vector<std::string> like_origins;
  std::variant<std::monostate, ResolvedGrating, ResolvedHeightmap, ResolvedPattern> texture;
  std::optional<Param> quantize_bits;      // heights rounded to this many bits before the gradient
  std::optional<Param> max_lateral_force;  // N: the texture's target maximum lateral force
  std::optional<Param> roughness;          // the ratio-scale roughness asked for, if any
  std::optional<Param> spring;             // N/m
  std::optional<Param> damper;             // N*s/m
  std::optional<Param> friction_coefficient;  // mu of Coulomb friction (`slipperiness`; docs/FORCE_LAWS.md, Friction)
  std::vector<PerceptTarget> percepts;     // viscosity, slipperiness, softness, bumpiness targets
  std::vector<ResolvedLaw> laws;           // force laws and physics models, summed in order
  std::optional<Param> energy_budget;      // J, for non-passive laws
  std::optional<Param> energy_refill;      // W
  Param size_width, size_height;           // m
  bool extrapolate = false;
  // Library metadata of this material's own file (not inherited through `like`).
  std::string family, licence, deprecated_by;
  std::vector<std::string> aliases;
};

}  // namespace sandpaper::compiler
