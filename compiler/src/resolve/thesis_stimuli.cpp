// The thesis' stimuli by name (Minsky 1995, 3.5, 4.3, Table 8, Appendix A): name -> material text.
#include "sandpaper/compiler/thesis_stimuli.hpp"

#include <cmath>
#include <regex>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "sandpaper/compiler/patterns.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::compiler {
namespace {

constexpr const char* kDataFile = "thesis/version1.toml";
constexpr int kJoystickUnitsPerLevel = 40;  // Table 8: level 1 = 40, 3 = 120, 10 = 400, 19 = 760 ju
constexpr int kJoystickFullScale = 2048;    // Table 8: "command amplitude (range 0-2048)"

// Readings from version1.toml.
struct Version1Data {
  double base_pu = 0, fless_pu = 0, fmore_pu = 0, fmost_pu = 0;
  std::string reference;  // the stimulus whose MaxGradient is felt at base_pu (4.5.2: force proportional to it)
  double stripes_weak_pu = 0, stripes_strong_pu = 0;
  double stripes_kernel_px = 0, seed = 0, patch_px = 0;
  double law_force_pu = 0, law_at_mm = 0, law_at_m_per_s = 0, law_period_mm = 0;
};

double number_at(const toml::table& t, const char* section, const char* key, const std::string& file) {
  auto v = t[section][key].value<double>();
  if (!v) throw std::runtime_error(file + ": [" + section + "] " + key + " is missing or not a number");
  return *v;
}

toml::table parse_data(const std::filesystem::path& library_dir, std::string& file) {
  auto path = library_dir / kDataFile;
  file = path.string();
  try {
    return toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << file << ": " << e.description();
    throw std::runtime_error(os.str());
  }
}

Version1Data load_data(const std::filesystem::path& library_dir) {
  std::string file;
  toml::table t = parse_data(library_dir, file);
  Version1Data d;
  d.base_pu = number_at(t, "forces", "base_pu", file);
  d.fless_pu = number_at(t, "forces", "Fless_pu", file);
  d.fmore_pu = number_at(t, "forces", "Fmore_pu", file);
  d.fmost_pu = number_at(t, "forces", "Fmost_pu", file);
  auto reference = t["forces"]["reference"].value<std::string>();
  if (!reference) throw std::runtime_error(file + ": [forces] reference is missing or not a string");
  d.reference = *reference;
  d.stripes_weak_pu = number_at(t, "forces", "stripes_weak_pu", file);
  d.stripes_strong_pu = number_at(t, "forces", "stripes_strong_pu", file);
  d.stripes_kernel_px = number_at(t, "patterns", "stripes_kernel_px", file);
  d.seed = number_at(t, "patterns", "seed", file);
  d.patch_px = number_at(t, "patterns", "patch_px", file);
  d.law_force_pu = number_at(t, "laws", "force_pu", file);
  d.law_at_mm = number_at(t, "laws", "at_displacement_mm", file);
  d.law_at_m_per_s = number_at(t, "laws", "at_speed_m_per_s", file);
  d.law_period_mm = number_at(t, "laws", "period_mm", file);
  return d;
}

// A length of `px` thesis pixels (0.37 mm) in mm, exactly as the decimal it is: 15 -> "5.55".
std::string px_mm(long long px) {
  long long hundredths = px * 37;
  std::string s = std::to_string(hundredths / 100);
  long long frac = hundredths % 100;
  if (frac) s += (frac % 10 ? "." + std::string(frac < 10 ? "0" : "") + std::to_string(frac) : "." + std::to_string(frac / 10));
  return s + " mm";
}

std::string sig(double v, int digits = 6) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

std::string force_suffix_pu(const std::string& suffix, const Version1Data& d, double& pu) {
  if (suffix == "Fless") pu = d.fless_pu;
  else if (suffix == "Fmore") pu = d.fmore_pu;
  else if (suffix == "Fmost") pu = d.fmost_pu;
  else pu = d.base_pu;
  return suffix.empty() ? "base force" : suffix;
}

const char* kVersion1Origin =
    "thesis stimulus generator (Minsky 1995, 3.5.1 and ch. 4; force proportional to the stimulus' MaxGradient (4.5.2), "
    "scale a reading from library/thesis/version1.toml)";

std::string version1_text(const std::string& name, const std::string& describes, const std::string& statement,
                          double pu, const std::string& force_note, const Version1Data& d) {
  std::ostringstream os;
  os << "# " << name << ", made by the thesis stimulus generator (compiler/src/resolve/thesis_stimuli.cpp).\n"
     << "# Force: " << sig(pu) << " pu (" << force_note << "), a reading: the OCR loses each version-1\n"
     << "# stimulus's force (library/thesis/version1.toml, docs/TEXTURES.md, \"Version-1 forces\").\n"
     << "material \"" << name << "\" {\n"
     << "  describes \"" << describes << "\"\n"
     << "  " << statement << (statement.rfind("force ", 0) == 0 ? "" : " amplitude " + sig(pu) + " pu") << "\n";
  if (statement.rfind("pattern ", 0) == 0) os << "  quantize 8 bit\n";
  os << "  size " << px_mm(static_cast<long long>(d.patch_px)) << "\n}\n";
  return os.str();
}

// Kernel as spelled in a name: "2", ".25", "0.25" (Appendix A's fine patterns), or none.
std::string kernel_options(const std::string& k1, const std::string& k2) {
  std::string s;
  auto spelled = [](const std::string& k) { return k[0] == '.' ? "0" + k : k; };
  if (!k1.empty()) s += " kernel " + spelled(k1);
  if (!k2.empty()) s += " refilter " + spelled(k2);
  return s;
}

std::string kernel_words(const std::string& k1, const std::string& k2) {
  if (k1.empty()) return "unsmoothed";
  std::string s = "Gaussian kernel " + k1;
  if (!k2.empty()) s += ", refiltered with kernel " + k2;
  return s;
}

Param px_param(double px) { return Param{px * kThesisPixel_m, "", Layer::Default, "", {}}; }
Param number_param(double v) { return Param{v, "", Layer::Default, "", {}}; }
double kernel_value(const std::string& k) { return std::stod(k[0] == '.' ? "0" + k : k); }

// A version-1 pattern as the generator states it, resolved directly (no text round trip).
ResolvedPattern v1_pattern(PatternKind kind, long long valley, long long hill, long long offset, const std::string& k1,
                           const std::string& k2, long long feature, double seed) {
  ResolvedPattern p;
  p.kind = kind;
  p.pixel = px_param(1);
  if (kind == PatternKind::Perlin) {
    p.feature = px_param(static_cast<double>(feature));
    p.seed = number_param(seed);
  } else {
    p.valley = px_param(static_cast<double>(valley));
    p.hill = px_param(static_cast<double>(hill));
    if (offset) p.offset = px_param(static_cast<double>(offset));
  }
  if (!k1.empty()) p.kernel = number_param(kernel_value(k1));
  if (!k2.empty()) p.refilter = number_param(kernel_value(k2));
  return p;
}

// 4.5.2's MaxGradient: the largest |h(i+1) - h(i-1)| of the stimulus' 8-bit height array, height steps.
std::optional<double> max_gradient_steps(const ResolvedPattern& p, const Version1Data& d) {
  schema::HeightFieldTerm field;
  Diagnostics diags;
  std::string summary;
  double peak = 0;
  const double patch = d.patch_px * kThesisPixel_m;
  if (!make_pattern_field(p, patch, patch, 8, 1.0, field, diags, summary, &peak)) return -1.0;  // cannot be made (E0304)
  return peak;
}

// The reference stimulus' MaxGradient ([forces] reference: a bars or grid name).
std::optional<double> reference_gradient(const Version1Data& d) {
  static const std::regex name(R"((bars|grid)B(\d+)W(\d+)_(\d+))");
  std::smatch m;
  if (!std::regex_match(d.reference, m, name)) return std::nullopt;
  return max_gradient_steps(v1_pattern(m[1] == "grid" ? PatternKind::Grid : PatternKind::Bars, std::stoll(m[2].str()),
                                       std::stoll(m[3].str()), 0, m[4].str(), "", 0, 0),
                            d);
}

// 4.5.2: "The maximum force from any stimulus is proportional to the maximum height gradient that
// occurs in its height array": `pu` (the variant's force at the reference's gradient) scaled by the
// stimulus' MaxGradient over the reference's; `note` says so. Returns why not, or "".
std::string proportional_force(const std::optional<double>& g, const Version1Data& d, double& pu, std::string& note) {
  const auto g_ref = reference_gradient(d);
  if (!g_ref || !(*g_ref > 0)) return "the reference stimulus " + d.reference + " of [forces] has no slope";
  if (g && *g < 0) return "its height array cannot be made: it is past the pattern limits (E0304: pixels, kernel and smoothing time)";
  if (!g || !(*g > 0)) return "its height array has no slope, so no force";
  const double at_reference = pu;
  pu = at_reference * *g / *g_ref;
  note += ", " + sig(at_reference) + " pu x MaxGradient " + sig(*g, 4) + " / " + sig(*g_ref, 4) + " height steps of " +
          d.reference + " (4.5.2)";
  return {};
}

ThesisLookup make(ThesisStimulus s) { return ThesisLookup{std::move(s), {}}; }
ThesisLookup fail(std::string why) { return ThesisLookup{std::nullopt, std::move(why)}; }

}  // namespace

const std::vector<std::string>& thesis_table8_names() {
  static const std::vector<std::string> names{"a1p7",   "a3p7",    "a3p12",   "a3p25",   "a3p50",   "a3p100",
                                              "a10p7",  "a10p12",  "a10p25",  "a10p50",  "a10p100", "a19p100"};
  return names;
}

ThesisLookup find_thesis_stimulus(const std::string& name, const std::filesystem::path& library_dir) {
  static const std::string K = R"((\d+(?:\.\d+)?|\.\d+))";
  static const std::regex bars("bars" R"(B(\d+)W(\d+))" "(?:_" + K + ")?(?:_" + K + ")?" "(Fless|Fmore|Fmost)?");
  static const std::regex grid("grid" R"(B(\d+)W(\d+)(?:off(\d+))?)" "(?:_" + K + ")?(?:_" + K + ")?" "(Fless|Fmore|Fmost)?");
  static const std::regex perlin(R"(perlin(\d+)(Fless|Fmore|Fmost)?)");
  static const std::regex noise(R"(Noise(\d+))");
  static const std::regex stripes(R"(2Stripes(Weak|Strong))");
  // Chapter 4's non-texturals and every prototype of Appendix B's Texture menu, by its own name.
  static const std::regex law(
      R"(Nothing|Bump|Slick|Spring|Viscous|AntiViscous|ATNSpring|Nap|Null|Bowl|Wave|Cusp|Triangle|Const|Ridge|Minus|Circle|Buckle)");
  // Table 8's levels are whole; one decimal (a8.5p18 = 340 ju) names Table 6's amplitudes, which are
  // whole program units (10 pu per level), in the same scheme.
  static const std::regex table8(R"([aA](\d+(?:\.\d)?)[pP](\d+))");
  std::smatch m;

  if (std::regex_match(name, m, table8)) {
    // Version-2 (3.5.2, Table 8): level l commands 40 l joystick units; the period is in 0.1 mm.
    const std::string level_text = m[1].str().substr(0, 11);
    const auto dot = level_text.find('.');
    const long long level_tenths = std::stoll(level_text.substr(0, dot)) * 10 +
                                   (dot == std::string::npos ? 0 : std::stoll(level_text.substr(dot + 1)));
    const long long tenths = std::stoll(m[2].str().substr(0, 9));
    if (level_tenths < 1 || level_tenths * kJoystickUnitsPerLevel > kJoystickFullScale * 10)
      return fail(name + ": force level " + m[1].str() + " commands " + sig(static_cast<double>(level_tenths) * kJoystickUnitsPerLevel / 10) +
                  " joystick units; levels run from 0.1 to 51.2 (4 to 2048 joystick units, the joystick's full scale)");
    if (tenths < 1) return fail(name + ": the period is in tenths of a millimetre and must be at least 1 (0.1 mm)");
    std::ostringstream os;
    const std::string period = sig(static_cast<double>(tenths) / 10.0) + " mm";
    const long long ju = level_tenths * kJoystickUnitsPerLevel / 10;  // whole: 40 / 10 = 4 ju per tenth
    const std::string level = sig(static_cast<double>(level_tenths) / 10.0);
    os << "# " << name << ", made by the thesis stimulus generator (compiler/src/resolve/thesis_stimuli.cpp).\n"
       << "# Minsky 1995 Table 8: force level " << level << " = command amplitude " << ju
       << " joystick units; equal hill and valley widths;\n"
       << "# the version-2 seed grating (3.5.2), 8-bit, repeated every " << period << ".\n"
       << "material \"" << name << "\" {\n"
       << "  describes \"Minsky 1995 version-2 grating " << name << ": force level " << level << " (" << ju
       << " ju), period " << period << "\"\n"
       << "  grating period " << period << " hill 50% amplitude " << ju << " ju\n"
       << "  quantize 8 bit\n}\n";
    return make({name, os.str(), "thesis stimulus generator (Minsky 1995, 3.5.2 and Table 8)"});
  }

  enum class Kind { None, Bars, Grid, Perlin, Noise, Stripes, Law };
  Kind kind = Kind::None;
  if (std::regex_match(name, m, bars)) kind = Kind::Bars;
  else if (std::regex_match(name, m, grid)) kind = Kind::Grid;
  else if (std::regex_match(name, m, perlin)) kind = Kind::Perlin;
  else if (std::regex_match(name, m, noise)) kind = Kind::Noise;
  else if (std::regex_match(name, m, stripes)) kind = Kind::Stripes;
  else if (std::regex_match(name, m, law)) kind = Kind::Law;
  if (kind == Kind::None) return {};

  Version1Data d;
  try {
    d = load_data(library_dir);
  } catch (const std::exception& e) {
    return fail(std::string("`") + name + "` is a thesis stimulus, but its data file cannot be read: " + e.what());
  }
  auto px = [&](const std::ssub_match& s) { return std::stoll(s.str().substr(0, 6)); };

  if (kind == Kind::Bars || kind == Kind::Grid) {
    const bool is_grid = kind == Kind::Grid;
    const long long valley = px(m[1]), hill = px(m[2]);
    const long long offset = is_grid && m[3].matched ? px(m[3]) : 0;
    const std::string k1 = m[is_grid ? 4 : 3].str(), k2 = m[is_grid ? 5 : 4].str(), suffix = m[is_grid ? 6 : 5].str();
    if (valley < 1 || hill < 1) return fail(name + ": valley and hill need at least one pixel each");
    // The name's kernels get the bound a `pattern ... kernel N` statement gets (else a name such as
    // gridB5W5_1777...7 overflows the blur radius).
    for (const auto& k : {k1, k2})
      if (!k.empty() && !(kernel_value(k) <= kMaxPatternKernel))
        return fail(name + ": kernel " + k + " is more than the largest kernel, " + sig(kMaxPatternKernel) + " px");
    double pu = 0;
    std::string force_note = force_suffix_pu(suffix, d, pu);
    const auto g = max_gradient_steps(v1_pattern(is_grid ? PatternKind::Grid : PatternKind::Bars, valley, hill, offset, k1, k2, 0, 0), d);
    if (const std::string why = proportional_force(g, d, pu, force_note); !why.empty()) return fail(name + ": " + why);
    std::string stmt = std::string("pattern ") + (is_grid ? "grid" : "bars") + " valley " + px_mm(valley) + " hill " +
                       px_mm(hill) + (offset ? " offset " + px_mm(offset) : "") + kernel_options(k1, k2);
    std::string describes = std::string("Minsky 1995 version-1 ") + (is_grid ? "grid " : "grating ") + name + ": valley " +
                            std::to_string(valley) + " px, hill " + std::to_string(hill) + " px" +
                            (offset ? ", rows offset " + std::to_string(offset) + " px" : "") + ", " +
                            kernel_words(k1, k2) + ", " + force_note + "; 1 px = 0.37 mm";
    return make({name, version1_text(name, describes, stmt, pu, force_note, d), kVersion1Origin});
  }
  if (kind == Kind::Perlin) {
    const long long feature = px(m[1]);
    if (feature < 1) return fail(name + ": the feature size needs at least one pixel");
    double pu = 0;
    std::string force_note = force_suffix_pu(m[2].str(), d, pu);
    const auto g = max_gradient_steps(v1_pattern(PatternKind::Perlin, 0, 0, 0, "", "", feature, d.seed), d);
    if (const std::string why = proportional_force(g, d, pu, force_note); !why.empty()) return fail(name + ": " + why);
    std::string stmt = "pattern perlin feature " + px_mm(feature) + " seed " + sig(d.seed);
    std::string describes = "Minsky 1995 version-1 Perlin texture " + name + ": lattice " + std::to_string(feature) +
                            " px, " + force_note + "; 1 px = 0.37 mm";
    return make({name, version1_text(name, describes, stmt, pu, force_note, d), kVersion1Origin});
  }
  if (kind == Kind::Noise) {
    const double pu = static_cast<double>(px(m[1]));
    if (pu < 1) return fail(name + ": the force, in program units, must be at least 1");
    std::string stmt = "pattern noise seed " + sig(d.seed);
    std::string describes = "Minsky 1995 non-textural " + name + ": random heights pixel by pixel, high forces "
                            "alternating closely (jitter), " + sig(pu) + " pu";
    return make({name, version1_text(name, describes, stmt, pu, "the name's number", d), kVersion1Origin});
  }
  if (kind == Kind::Stripes) {
    const bool strong = m[1].str() == "Strong";
    const double pu = strong ? d.stripes_strong_pu : d.stripes_weak_pu;
    std::string stmt = "pattern stripes count 2 kernel " + sig(d.stripes_kernel_px);
    std::string describes = "Minsky 1995 non-textural " + name + ": two very wide stripes across the patch, " +
                            (strong ? "strong" : "weak") + " force";
    return make({name, version1_text(name, describes, stmt, pu, strong ? "strong" : "weak", d), kVersion1Origin});
  }
  // Non-textural force laws (4.3, Appendix B); constants are readings ([laws] in the data file).
  const double force_N = d.law_force_pu * schema::find_unit("pu")->to_si;
  const double k = force_N / (d.law_at_mm * 1e-3), b = force_N / d.law_at_m_per_s;
  const std::string n = m[0].str();
  const double period_mm = d.law_period_mm, lead_s = 0.02, lag_s = 0.1;
  const std::string at_mm = sig(d.law_force_pu) + " pu at " + sig(d.law_at_mm) + " mm from the centre";
  const std::string at_speed = sig(d.law_force_pu) + " pu at " + sig(d.law_at_m_per_s) + " m/s";
  const std::string amp = sig(force_N) + " N", per = sig(period_mm) + " mm";
  std::string stmt, describes;
  if (n == "Nothing" || n == "Null") {
    stmt = "force " + n;
    describes = "Minsky 1995 " + std::string(n == "Nothing" ? "non-textural Nothing" : "Texture-menu Null") + ": no force";
  } else if (n == "Spring" || n == "Bump") {
    stmt = "force " + n + " stiffness " + sig(k) + " N/m";
    describes = "Minsky 1995 non-textural " + n + (n == "Spring" ? ": F = -k p, a bowl" : ": F = k p, a dome") + ", " + at_mm;
  } else if (n == "Viscous" || n == "Slick" || n == "AntiViscous") {
    stmt = std::string("force ") + (n == "Viscous" ? "Viscous" : "AntiViscous") + " damping " + sig(b) + " N*s/m";
    describes = "Minsky 1995 " + std::string(n == "AntiViscous" ? "Texture-menu " : "non-textural ") + n +
                (n == "Viscous" ? ": F = -b v, like oil" : ": F = +b v, like ice") + ", " + at_speed;
  } else if (n == "Nap") {
    stmt = "force Nap damping " + sig(b) + " N*s/m";
    describes = "Minsky 1995 Texture-menu Nap: F_x = -b v_x, F_y = |b v_y|, like velvet, " + at_speed;
  } else if (n == "Bowl") {
    // F = -k p sqrt(|p| / r) equals the linear spring at r: the reading's 40 mm.
    stmt = "force Bowl stiffness " + sig(k) + " N/m radius " + sig(d.law_at_mm) + " mm";
    describes = "Minsky 1995 Texture-menu Bowl: a spring growing as |p|^1.5, " + at_mm;
  } else if (n == "Circle") {
    stmt = "force Circle stiffness " + sig(k) + " N/m";
    describes = "Minsky 1995 Texture-menu Circle: a field k p turned a quarter turn, " + at_mm;
  } else if (n == "Buckle") {
    stmt = "force Buckle radial " + sig(k) + " N/m tangential " + sig(k) + " N/m";
    describes = "Minsky 1995 Texture-menu Buckle: radial and quarter-turn gains, each " + at_mm;
  } else if (n == "Wave" || n == "Cusp" || n == "Triangle") {
    stmt = "force " + n + " amplitude " + amp + " period " + per;
    describes = "Minsky 1995 " + std::string(n == "Triangle" ? "3.4 procedural triangle wave" : "Texture-menu " + n) +
                ": amplitude " + sig(d.law_force_pu) + " pu, period " + per + " on each axis";
  } else if (n == "Ridge") {
    // F_x = k ((p_x mod wavelength) - width) spans -k width .. k (wavelength - width): width = half.
    const double width_mm = period_mm / 2;
    stmt = "force Ridge stiffness " + sig(force_N / (width_mm * 1e-3)) + " N/m wavelength " + per + " width " + sig(width_mm) + " mm";
    describes = "Minsky 1995 Texture-menu Ridge: ridges every " + per + " along x, " + sig(d.law_force_pu) + " pu at their edges";
  } else if (n == "Const") {
    stmt = "force Const x " + amp + " y 0 N";
    describes = "Minsky 1995 Texture-menu Const: a steady " + sig(d.law_force_pu) + " pu toward +x";
  } else if (n == "Minus") {
    stmt = "force Minus stiffness " + sig(b / lead_s) + " N/m lead " + sig(lead_s * 1e3) + " ms";
    describes = "Minsky 1995 Texture-menu Minus: a spring to where the hand will be 20 ms ahead, " + at_speed;
  } else {  // ATNSpring
    stmt = "force ATNSpring stiffness " + sig(b / lag_s) + " N/m lag " + sig(lag_s * 1e3) + " ms";
    describes = "Minsky 1995 Texture-menu ATNSpring: pushed from a point trailing the hand by 100 ms, " + at_speed;
  }
  std::ostringstream os;
  os << "# " << n << ", made by the thesis stimulus generator (compiler/src/resolve/thesis_stimuli.cpp).\n"
     << "# Constants are readings ([laws] in library/thesis/version1.toml): the thesis gives none.\n"
     << "material \"" << n << "\" {\n"
     << "  describes \"" << describes << "\"\n"
     << "  " << stmt << "\n"
     << "  size " << px_mm(static_cast<long long>(d.patch_px)) << "\n}\n";
  return make({n, os.str(),
               "thesis stimulus generator (Minsky 1995, 4.3 and Appendix B's Texture menu; constants a reading from "
               "library/thesis/version1.toml)"});
}

std::vector<ListedStimulus> thesis_version1_list(const std::filesystem::path& library_dir) {
  std::string file;
  toml::table t = parse_data(library_dir, file);
  const auto* arr = t["stimulus"].as_array();
  if (!arr) throw std::runtime_error(file + ": no [[stimulus]] entries");
  std::vector<ListedStimulus> out;
  for (const auto& e : *arr) {
    const auto* s = e.as_table();
    auto name = s ? (*s)["name"].value<std::string>() : std::nullopt;
    auto from = s ? (*s)["read_from"].value<std::string>() : std::nullopt;
    if (!name || !from) throw std::runtime_error(file + ": a [[stimulus]] without name or read_from");
    out.push_back({*name, *from, (*s)["note"].value_or(std::string())});
  }
  return out;
}

}  // namespace sandpaper::compiler
