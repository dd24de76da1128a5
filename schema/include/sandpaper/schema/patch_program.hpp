#pragma once
// The patch program: what the compiler hands the runtime. Everything the servo tick needs is
// precomputed here (force tables in newtons), so the tick only samples and sums (thesis 3.4;
// Appendix B "Texture" and "Arrays" patch classes). SI units throughout. Format: docs/PATCH_FORMAT.md.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace sandpaper::schema {

inline constexpr std::uint32_t kPatchFormatVersion = 3;

// F = -k (p - centre), p the hand position relative to the patch centre (thesis EQ 1, App. B Spring).
struct SpringTerm {
  double stiffness_N_per_m = 0;
  double centre_m[2] = {0, 0};
};

// F = -b v (thesis EQ 2, App. B Viscous).
struct DamperTerm {
  double damping_Ns_per_m = 0;
};

// A grating: the lateral force depends only on u = p . n, n = (cos orientation, sin orientation).
// force_N[i] is the force along n at u = (i / size) * period; the runtime interpolates linearly
// and wraps. Thesis 3.5.2 (version-2 seed, scaled and repeated to the period).
struct GratingTerm {
  double period_m = 0;
  double orientation_rad = 0;
  std::vector<float> force_N;  // one period, size >= 2
};

// A height field's lateral-force gradient F = -k grad h sampled on a regular grid (thesis 3.4,
// EQ 12-13), in newtons. Sample (ix, iy) sits at origin + (ix * spacing_x, iy * spacing_y),
// row-major with x fastest. Outside the grid the force is zero unless `repeat` wraps it.
struct HeightFieldTerm {
  std::uint32_t nx = 0, ny = 0;
  double origin_m[2] = {0, 0};
  double spacing_m[2] = {0, 0};
  bool repeat = false;
  std::vector<float> force_x_N;  // nx * ny
  std::vector<float> force_y_N;  // nx * ny
};

// Appendix B Const: F = (fx, fy), everywhere on the patch.
struct ConstantForceTerm {
  double force_N[2] = {0, 0};
};

// Appendix B Nap: F_x = -b v_x, F_y = |b v_y| (direction-dependent, like velvet). Not passive:
// the y force does work on a hand moving toward +y.
struct NapTerm {
  double damping_Ns_per_m = 0;
};

// Per-axis periodic force laws of position, each axis independent (u = p_x or p_y, P = period):
//   Sine     (App. B Wave):  F = -A sin(2 pi u / P)
//   Sawtooth (App. B Cusp):  F = A (2 frac(|u| / P) - 1)                  reading of "[|p/f| mod 2A] - A"
//   Triangle (thesis 3.4):   F = -A (2 frac(u / P) - 1)                   force toward each local wave centre
// docs/TEXTURES.md gives the readings.
enum class PeriodicShape : std::uint8_t { Sine = 0, Sawtooth = 1, Triangle = 2 };
struct PeriodicTerm {
  PeriodicShape shape = PeriodicShape::Sine;
  double amplitude_N = 0;
  double period_m = 0;
  bool on_x = true, on_y = true;
};

// Appendix B Ridge: F_x = k ((p_x mod wavelength) - ridge width), F_y = 0. The modulo is floored, into
// [0, wavelength), so the ridges repeat alike on both sides of the centre. wavelength > 0.
struct RidgeTerm {
  double stiffness_N_per_m = 0;
  double wavelength_m = 0;
  double ridge_width_m = 0;
};

// Appendix B Bowl (reading: a spring whose force grows as |p|^1.5): F = -k p sqrt(|p| / r), equal to
// a linear spring of stiffness k at radius r (> 0).
struct BowlTerm {
  double stiffness_N_per_m = 0;
  double radius_m = 0;
};

// Appendix B Circle and Buckle: F = g_r p + g_t R90 p, R90 p = (-p_y, p_x). Circle is (0, k);
// Buckle is (v1, v2); Bump (F = k p) is (k, 0). A tangential gain makes the field non-conservative.
struct LinearFieldTerm {
  double radial_N_per_m = 0;
  double tangential_N_per_m = 0;
};

// A linear spring (thesis 3.2.2): pulls only along the unit direction n = (cos a, sin a) toward the
// line through `centre` normal to n: F = -k ((p - centre) . n) n.
struct LinearSpringTerm {
  double stiffness_N_per_m = 0;
  double orientation_rad = 0;
  double centre_m[2] = {0, 0};
};

// Appendix B Minus: F = k (p - m), m the position predicted `lead` ahead from the hand's position,
// velocity and acceleration: m - p = v lead + a lead^2 / 2 (lead >= 0): a damper and an added mass
// (docs/TEXTURES.md, "Minus and ATNSpring"). Metered by the energy bound (sampled acceleration).
struct MinusTerm {
  double stiffness_N_per_m = 0;
  double lead_s = 0;
};

// Appendix B ATNSpring: F = k (p - m), m a point that follows the hand with a first-order lag:
// dm/dt = (p - m) / lag, lag > 0. State: m (runtime). Not passive: m trails the hand, so the force
// pushes along its recent motion (docs/TEXTURES.md, "Minus and ATNSpring"); k >= 0.
struct FollowerSpringTerm {
  double stiffness_N_per_m = 0;
  double lag_s = 0;
};

// Thesis 3.2.2 physics patches: one or two point masses in a chain hand - mass 0 - mass 1, each link
// a spring and damper; each mass also feels ground damping and a constant gravity (the brick hanging
// from a spring: one mass, gravity (0, -9.81)). The hand feels link 0: F = -k0 (p - x0) - c0 (v - v0).
// State: positions and velocities of the masses (runtime), starting at rest hanging from the hand under
// gravity. Masses > 0; springs and dampers >= 0 (else the chain itself is unstable).
struct PointMassesTerm {
  std::uint32_t count = 1;                 // 1 or 2
  double mass_kg[2] = {0, 0};
  double stiffness_N_per_m[2] = {0, 0};    // link i joins mass i to the hand (i = 0) or to mass i-1
  double damping_Ns_per_m[2] = {0, 0};     // dampers in parallel with the links
  double ground_damping_Ns_per_m = 0;      // each mass against the ground
  double gravity_m_s2[2] = {0, 0};
};

// Thesis 3.2.2 Attractor: a spring to a light object moving on a swirling path,
//   q(t) = centre + radius * (1 + swirl sin(3 theta)) / (1 + swirl) * (cos theta, sin theta),
//   theta = 2 pi t / period; F = -k (p - q(t)). State: t (runtime). Not passive: it drives the hand.
//   period > 0, radius >= 0, swirl > -1 (the radius divides by 1 + swirl).
struct AttractorTerm {
  double stiffness_N_per_m = 0;
  double radius_m = 0;
  double period_s = 0;
  double swirl = 0;  // 0 = a circle
  double centre_m[2] = {0, 0};
};

// Coulomb friction with stick-slip against a stated press force (a joystick has no normal force:
// docs/FORCE_LAWS.md, "Friction"). The hand is tied by a spring of `stiffness` to an adhesion point w
// (Hayward & Armstrong 2000's presliding spring; Karnopp 1985's stick band): F = -k (p - w). Sticking,
// w stays until |p - w| passes mu_static P / k, then the contact slides: w is dragged behind the hand
// at mu_kinetic P / k, so |F| = mu_kinetic P, until the hand's speed falls below `stick_speed` or it
// turns back, when the contact sticks again. w only ever moves toward the hand, so the term is
// passive. State: w and sticking (runtime). 0 <= mu_kinetic <= mu_static, P > 0, k > 0.
struct FrictionTerm {
  double static_coefficient = 0;
  double kinetic_coefficient = 0;
  double press_N = 0;
  double stiffness_N_per_m = 0;
  double stick_speed_m_s = 0;
};

// Friction that depends on the way the contact slides across a nap (velvet, fur: "different properties
// when stroked in different directions", thesis 7.4.1). Sliding along n = (cos nap, sin nap), "with
// the nap", the coefficients are static_ and kinetic_coefficient; along -n, against it, they are the
// against_ ones; in between they mix by (1 - cos angle) / 2, the angle between n and p - w. Otherwise as
// FrictionTerm (the same adhesion point and stick band), so passive. State: w and sticking (runtime).
struct NapFrictionTerm {
  double static_coefficient = 0;
  double kinetic_coefficient = 0;
  double against_static_coefficient = 0;
  double against_kinetic_coefficient = 0;
  double press_N = 0;
  double stiffness_N_per_m = 0;
  double stick_speed_m_s = 0;
  double nap_orientation_rad = 0;
};

// Each kind's tag, names, passivity, state and field list: schema::terms::Kind (term_kinds.hpp), which
// drives the patch file, the JSON view and the runtime's checks (docs/PATCH_FORMAT.md, "Adding a term kind").
using Term = std::variant<SpringTerm, DamperTerm, GratingTerm, HeightFieldTerm, ConstantForceTerm, NapTerm,
                          PeriodicTerm, RidgeTerm, BowlTerm, LinearFieldTerm, LinearSpringTerm, MinusTerm,
                          FollowerSpringTerm, PointMassesTerm, AttractorTerm, FrictionTerm, NapFrictionTerm>;

// Whether a term can only store and return energy it took from the hand (thesis 3.2.2 calls the others
// "non-physical"). Non-passive terms: negative damping (AntiViscous, Slick), Nap, Minus, ATNSpring,
// Attractor, and linear fields with a tangential gain (Circle, Buckle); each kind's entry in
// term_kinds.hpp says which. The runtime bounds the energy they inject.
bool is_passive(const Term& term);
// Whether the runtime keeps state for the term between ticks (FollowerSpring, PointMasses, Attractor,
// Friction).
bool has_state(const Term& term);

struct PatchProgram;
// Bytes of the program's sampled force tables (height-field and grating terms), which are nearly all
// of a textured program's memory: a height field at the image limit, 4096 x 4096, is 128 MiB.
std::uint64_t grid_bytes(const PatchProgram& program);

// Substeps of the point-mass integrator (semi-implicit Euler) for one tick of `dt_s` seconds: enough
// that each substep h keeps h * omega <= 0.25 and h * c / m <= 0.5, with omega and c / m bounded by
// Gershgorin's theorem from the chain's stiffness and damping. The runtime caps it at
// kMaxPointMassSubsteps; the compiler refuses materials that need more at the device's slowest rate.
inline constexpr std::uint32_t kMaxPointMassSubsteps = 64;
std::uint32_t point_mass_substeps(const PointMassesTerm& term, double dt_s);

// Where one number of the compiled program came from.
struct Provenance {
  std::string parameter;  // dotted name: "texture.period", "texture.max_lateral_force", "spring.stiffness"
  double value_si = 0;    // value in `si_unit`
  std::string si_unit;    // "m", "N", "N/m", "N*s/m", "rad", "1"
  std::string stated;     // as the source wrote it, e.g. "3.2 mm", "roughness 0.55"
  std::string layer;      // "representative", "perceptual", "physical", "default", "derived"
  std::string source;     // "examples/corduroy.hmat:5:3", "library corduroy (corduroy.hmat:6:3)", "calibration ..."
};

struct CompileWarning {
  std::string code;     // stable identifier, e.g. "W0301"
  std::string message;
};

// The device's command scale the program was compiled against (calibration/devices/<name>.toml).
// Forces in the program stay in newtons; a device driver turns them into commands with this scale
// (thesis 7.6.3: compiling is device-dependent). For a device whose scale is a table, the factors
// are the table's local slope at the program's maximum lateral force.
struct CommandScale {
  std::string device_file;                       // "calibration/devices/sandpaper-1995.toml"
  std::string command_unit;                      // "ju"
  double newtons_per_command_unit[2] = {1, 1};   // x, y
  std::int64_t command_max = 0;                  // largest command magnitude; 0: continuous (no quantization)
  double max_force_N = 0;                        // the device's maximum continuous force per axis
  bool calibrated = true;                        // false: the scale is assumed, not measured
};

struct PatchProgram {
  std::string name;        // material name, e.g. "corduroy/wide-wale"
  std::string describes;   // the representative intent, kept verbatim (thesis 1.5.2)
  std::string device;      // device calibration the program was compiled for, e.g. "sim"
  CommandScale command;    // that device's command scale
  double size_m[2] = {0.095, 0.095};  // patch width, height; centred on (0, 0)
  std::vector<Term> terms;            // summed each tick, in order
  double max_lateral_force_N = 0;     // texture's maximum lateral force over the patch less its rim
  double roughness = 0;               // ratio-scale roughness the map predicts for that force
  std::string roughness_map;          // id of the map used, e.g. "minsky1995-fig19"
  std::string roughness_map_file;     // its file, e.g. "calibration/maps/minsky1995-fig19.toml"
  // Energy the non-passive terms may put into the hand: a tank of `energy_budget_J` that refills at
  // `energy_refill_W` and with whatever those terms absorb (docs/RUNTIME.md, "Energy bound").
  double energy_budget_J = 0;
  double energy_refill_W = 0;
  std::vector<Provenance> provenance;
  std::vector<CompileWarning> warnings;
};

}  // namespace sandpaper::schema
