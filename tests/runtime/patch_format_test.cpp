// Patch format 2 (docs/PATCH_FORMAT.md): every term kind and the energy fields survive the file
// round trip, each kind has the tag the document gives, bad enumerations are refused, and the JSON
// view names each parameter with its unit.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <variant>

#include <zlib.h>

#include "runtime_test_support.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "sandpaper/schema/workspace_io.hpp"
#include "term_samples.hpp"

namespace sandpaper::runtime {
namespace {

using namespace testing;
using namespace schema;

bool same(const double (&a)[2], const double (&b)[2]) { return a[0] == b[0] && a[1] == b[1]; }

// Field-by-field equality, written out per kind so that a field the file forgets shows up.
bool same(const Term& x, const Term& y) {
  if (x.index() != y.index()) return false;
  if (const auto* a = std::get_if<SpringTerm>(&x)) {
    const auto& b = std::get<SpringTerm>(y);
    return a->stiffness_N_per_m == b.stiffness_N_per_m && same(a->centre_m, b.centre_m);
  }
  if (const auto* a = std::get_if<DamperTerm>(&x)) return a->damping_Ns_per_m == std::get<DamperTerm>(y).damping_Ns_per_m;
  if (const auto* a = std::get_if<GratingTerm>(&x)) {
    const auto& b = std::get<GratingTerm>(y);
    return a->period_m == b.period_m && a->orientation_rad == b.orientation_rad && a->force_N == b.force_N;
  }
  if (const auto* a = std::get_if<HeightFieldTerm>(&x)) {
    const auto& b = std::get<HeightFieldTerm>(y);
    return a->nx == b.nx && a->ny == b.ny && same(a->origin_m, b.origin_m) && same(a->spacing_m, b.spacing_m) &&
           a->repeat == b.repeat && a->force_x_N == b.force_x_N && a->force_y_N == b.force_y_N;
  }
  if (const auto* a = std::get_if<ConstantForceTerm>(&x)) return same(a->force_N, std::get<ConstantForceTerm>(y).force_N);
  if (const auto* a = std::get_if<NapTerm>(&x)) return a->damping_Ns_per_m == std::get<NapTerm>(y).damping_Ns_per_m;
  if (const auto* a = std::get_if<PeriodicTerm>(&x)) {
    const auto& b = std::get<PeriodicTerm>(y);
    return a->shape == b.shape && a->amplitude_N == b.amplitude_N && a->period_m == b.period_m && a->on_x == b.on_x &&
           a->on_y == b.on_y;
  }
  if (const auto* a = std::get_if<RidgeTerm>(&x)) {
    const auto& b = std::get<RidgeTerm>(y);
    return a->stiffness_N_per_m == b.stiffness_N_per_m && a->wavelength_m == b.wavelength_m &&
           a->ridge_width_m == b.ridge_width_m;
  }
  if (const auto* a = std::get_if<BowlTerm>(&x)) {
    const auto& b = std::get<BowlTerm>(y);
    return a->stiffness_N_per_m == b.stiffness_N_per_m && a->radius_m == b.radius_m;
  }
  if (const auto* a = std::get_if<LinearFieldTerm>(&x)) {
    const auto& b = std::get<LinearFieldTerm>(y);
    return a->radial_N_per_m == b.radial_N_per_m && a->tangential_N_per_m == b.tangential_N_per_m;
  }
  if (const auto* a = std::get_if<LinearSpringTerm>(&x)) {
    const auto& b = std::get<LinearSpringTerm>(y);
    return a->stiffness_N_per_m == b.stiffness_N_per_m && a->orientation_rad == b.orientation_rad &&
           same(a->centre_m, b.centre_m);
  }
  if (const auto* a = std::get_if<MinusTerm>(&x)) {
    const auto& b = std::get<MinusTerm>(y);
    return a->stiffness_N_per_m == b.stiffness_N_per_m && a->lead_s == b.lead_s;
  }
  if (const auto* a = std::get_if<FollowerSpringTerm>(&x)) {
    const auto& b = std::get<FollowerSpringTerm>(y);
    return a->stiffness_N_per_m == b.stiffness_N_per_m && a->lag_s == b.lag_s;
  }
  if (const auto* a = std::get_if<PointMassesTerm>(&x)) {
    const auto& b = std::get<PointMassesTerm>(y);
    return a->count == b.count && same(a->mass_kg, b.mass_kg) && same(a->stiffness_N_per_m, b.stiffness_N_per_m) &&
           same(a->damping_Ns_per_m, b.damping_Ns_per_m) && a->ground_damping_Ns_per_m == b.ground_damping_Ns_per_m &&
           same(a->gravity_m_s2, b.gravity_m_s2);
  }
  if (const auto* a = std::get_if<FrictionTerm>(&x)) {
    const auto& b = std::get<FrictionTerm>(y);
    return a->static_coefficient == b.static_coefficient && a->kinetic_coefficient == b.kinetic_coefficient &&
           a->press_N == b.press_N && a->stiffness_N_per_m == b.stiffness_N_per_m && a->stick_speed_m_s == b.stick_speed_m_s;
  }
  if (const auto* a = std::get_if<NapFrictionTerm>(&x)) {
    const auto& b = std::get<NapFrictionTerm>(y);
    return a->static_coefficient == b.static_coefficient && a->kinetic_coefficient == b.kinetic_coefficient &&
           a->against_static_coefficient == b.against_static_coefficient &&
           a->against_kinetic_coefficient == b.against_kinetic_coefficient && a->press_N == b.press_N &&
           a->stiffness_N_per_m == b.stiffness_N_per_m && a->stick_speed_m_s == b.stick_speed_m_s &&
           a->nap_orientation_rad == b.nap_orientation_rad;
  }
  const auto& a = std::get<AttractorTerm>(x);
  const auto& b = std::get<AttractorTerm>(y);
  return a.stiffness_N_per_m == b.stiffness_N_per_m && a.radius_m == b.radius_m && a.period_s == b.period_s &&
         a.swirl == b.swirl && same(a.centre_m, b.centre_m);
}

TEST(PatchFormat, EveryTermKindRoundTrips) {
  const auto kinds = every_term_kind();
  ASSERT_EQ(kinds.size(), std::variant_size_v<Term>);
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    SCOPED_TRACE(i);
    auto program = program_of({kinds[i]});
    const auto back = deserialize(serialize(program));
    ASSERT_EQ(back.terms.size(), 1u);
    EXPECT_TRUE(same(back.terms[0], kinds[i]));
  }
  // All at once, with the other shapes and a one-mass chain whose unused slot is kept as written.
  auto all = kinds;
  all.push_back(periodic(PeriodicShape::Sine, -0.5, 0.01, false, true));
  all.push_back(periodic(PeriodicShape::Triangle, 0.5, 0.02, true, true));
  auto one = one_mass(0.2, 80, 0.3, 0.05, -9.81);
  one.mass_kg[1] = 7;
  all.push_back(one);
  const auto back = deserialize(serialize(program_of(all)));
  ASSERT_EQ(back.terms.size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_TRUE(same(back.terms[i], all[i])) << i;
}

TEST(PatchFormat, EnergyFieldsRoundTrip) {
  auto program = program_of({damper(-2)});
  program.energy_budget_J = 0.0125;
  program.energy_refill_W = 0.003;
  const auto back = deserialize(serialize(program));
  EXPECT_EQ(back.energy_budget_J, 0.0125);
  EXPECT_EQ(back.energy_refill_W, 0.003);
}

// With empty strings the first term's tag sits at a fixed offset: header 32, three empty strings 12,
// command scale (two empty strings 8, two factors 16, command_max 8, max force 8, calibrated 1),
// size 16, force and roughness 16, empty map id and file 8, energy 16, term count 4.
constexpr std::size_t kFirstTagOffset = 32 + 12 + (8 + 16 + 8 + 8 + 1) + 16 + 16 + 8 + 16 + 4;

TEST(PatchFormat, CommandScaleAndMapFileRoundTrip) {
  auto program = program_of({damper(2)});
  program.command = {"calibration/devices/sandpaper-1995.toml", "ju", {0.0048, 0.0049}, 2048, 10.0, false};
  program.roughness_map_file = "calibration/maps/minsky1995-fig19.toml";
  const auto back = deserialize(serialize(program));
  EXPECT_EQ(back.command.device_file, program.command.device_file);
  EXPECT_EQ(back.command.command_unit, "ju");
  EXPECT_EQ(back.command.newtons_per_command_unit[0], 0.0048);
  EXPECT_EQ(back.command.newtons_per_command_unit[1], 0.0049);
  EXPECT_EQ(back.command.command_max, 2048);
  EXPECT_EQ(back.command.max_force_N, 10.0);
  EXPECT_FALSE(back.command.calibrated);
  EXPECT_EQ(back.roughness_map_file, program.roughness_map_file);
}

schema::PatchProgram bare(std::vector<Term> terms) {
  schema::PatchProgram program;
  program.terms = std::move(terms);
  return program;
}

TEST(PatchFormat, TagsAreTheDocumentedOnes) {
  const auto kinds = every_term_kind();
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const auto bytes = serialize(bare({kinds[i]}));
    std::uint32_t tag = 0;
    std::memcpy(&tag, bytes.data() + kFirstTagOffset, 4);
    // 16 is the compact height field (a second encoding of kind 4), so friction, the 16th kind, is 17.
    EXPECT_EQ(tag, i < 15 ? i + 1 : i + 2) << "docs/PATCH_FORMAT.md numbers the kinds in the variant's order";
  }
}

// Rewrites one payload byte and fixes the checksum, so that the reader's own checks are what refuse it.
std::vector<unsigned char> patched(std::vector<unsigned char> bytes, std::size_t offset, unsigned char value) {
  bytes[offset] = value;
  const auto crc = static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), bytes.data() + 32, static_cast<uInt>(bytes.size() - 32)));
  std::memcpy(bytes.data() + 24, &crc, 4);
  return bytes;
}

// Empty arrays are read without handing memcpy or fread a null pointer (undefined behaviour that
// UBSan reported in issue 16: run this under the asan preset to check it), then refused; a 1-row
// grid is read if it repeats, and refused if it does not.
TEST(PatchFormat, EmptyAndOneRowGrids) {
  HeightFieldTerm empty;
  empty.spacing_m[0] = empty.spacing_m[1] = 1e-3;
  for (const bool compact : {false, true}) {
    PatchWriteOptions options;
    options.compact_grids = compact;
    EXPECT_THROW(deserialize(serialize(bare({empty}), options)), PatchFormatError);
  }
  HeightFieldTerm row;
  row.nx = 35;
  row.ny = 1;
  row.spacing_m[0] = row.spacing_m[1] = 0.37e-3;
  row.force_x_N.assign(35, 0.5f);
  row.force_y_N.assign(35, 0.0f);
  row.repeat = true;
  EXPECT_NO_THROW(deserialize(serialize(bare({row}))));
  row.repeat = false;
  EXPECT_THROW(deserialize(serialize(bare({row}))), PatchFormatError);
}

// A workspace program whose size is denormal made the runtime's patch grid cast inf to an
// unsigned cell index (fuzz finding F2, issue 16): the reader refuses sizes outside the compiler's
// range for a quantity, and the grid's cell arithmetic stays defined whatever it is given.
TEST(PatchFormat, ImplausibleWorkspaceSizesAreRefused) {
  const auto dir = std::filesystem::temp_directory_path() / ("sandpaper-ws-size-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const double size : {2.78e-309, 1e-13, 3.1e78, std::numeric_limits<double>::infinity()}) {
    WorkspaceProgram ws;
    ws.size_m[1] = size;
    write_workspace_program_file(dir / "w.wsp", ws);
    EXPECT_THROW(read_workspace_program_file(dir / "w.wsp"), PatchFormatError) << size;
  }
  WorkspaceProgram ok;
  ok.size_m[0] = 1e-12;
  write_workspace_program_file(dir / "w.wsp", ok);
  EXPECT_NO_THROW(read_workspace_program_file(dir / "w.wsp"));
  std::filesystem::remove_all(dir);
}

TEST(PatchFormat, UnknownShapesAndCountsAreRefused) {
  const auto wave = serialize(bare({periodic(PeriodicShape::Sine, 1, 0.01)}));
  EXPECT_NO_THROW(deserialize(patched(wave, kFirstTagOffset + 4, 2)));
  EXPECT_THROW(deserialize(patched(wave, kFirstTagOffset + 4, 3)), PatchFormatError);
  const auto masses = serialize(bare({one_mass(0.1, 100, 0.1)}));
  EXPECT_NO_THROW(deserialize(patched(masses, kFirstTagOffset + 4, 2)));
  EXPECT_THROW(deserialize(patched(masses, kFirstTagOffset + 4, 3)), PatchFormatError);
  EXPECT_THROW(deserialize(patched(masses, kFirstTagOffset + 4, 0)), PatchFormatError);
  EXPECT_THROW(deserialize(patched(masses, kFirstTagOffset, 16)), PatchFormatError);  // no tag 16
}

TEST(PatchFormat, JsonNamesEveryParameterWithItsUnit) {
  auto program = program_of(every_term_kind());
  program.energy_budget_J = 0.02;
  program.energy_refill_W = 0.005;
  const auto j = to_json(program);
  EXPECT_EQ(j["energy_budget_J"], 0.02);
  EXPECT_EQ(j["energy_refill_W"], 0.005);
  const auto& t = j["terms"];
  ASSERT_EQ(t.size(), std::variant_size_v<Term>);
  EXPECT_EQ(t[4]["kind"], "constant_force");
  EXPECT_EQ(t[4]["force_N"], nlohmann::json({0.3, -0.2}));
  EXPECT_EQ(t[5]["kind"], "nap");
  EXPECT_EQ(t[5]["damping_Ns_per_m"], 2.0);
  EXPECT_EQ(t[5]["passive"], false);
  EXPECT_EQ(t[6]["kind"], "periodic");
  EXPECT_EQ(t[6]["shape"], "sawtooth");
  EXPECT_EQ(t[6]["amplitude_N"], 0.8);
  EXPECT_EQ(t[6]["period_m"], 0.004);
  EXPECT_EQ(t[6]["on_x"], true);
  EXPECT_EQ(t[6]["on_y"], false);
  EXPECT_EQ(t[6]["passive"], true);
  EXPECT_EQ(t[7]["kind"], "ridge");
  EXPECT_EQ(t[7]["wavelength_m"], 0.006);
  EXPECT_EQ(t[7]["ridge_width_m"], 0.002);
  EXPECT_EQ(t[7]["stiffness_N_per_m"], 300.0);
  EXPECT_EQ(t[8]["kind"], "bowl");
  EXPECT_EQ(t[8]["radius_m"], 0.03);
  EXPECT_EQ(t[9]["kind"], "linear_field");
  EXPECT_EQ(t[9]["radial_N_per_m"], -50.0);
  EXPECT_EQ(t[9]["tangential_N_per_m"], 40.0);
  EXPECT_EQ(t[9]["passive"], false);
  EXPECT_EQ(t[10]["kind"], "linear_spring");
  EXPECT_EQ(t[10]["orientation_rad"], 0.7);
  EXPECT_EQ(t[10]["centre_m"], nlohmann::json({0.001, -0.002}));
  EXPECT_EQ(t[11]["kind"], "minus");
  EXPECT_EQ(t[11]["lead_s"], 0.02);
  EXPECT_EQ(t[12]["kind"], "follower_spring");
  EXPECT_EQ(t[12]["lag_s"], 0.05);
  EXPECT_EQ(t[12]["passive"], false);  // ATNSpring pushes along the recent motion (issue 15)
  EXPECT_EQ(t[13]["kind"], "point_masses");
  EXPECT_EQ(t[13]["count"], 2);
  EXPECT_EQ(t[13]["mass_kg"], nlohmann::json({0.05, 0.03}));
  EXPECT_EQ(t[13]["stiffness_N_per_m"], nlohmann::json({200.0, 150.0}));
  EXPECT_EQ(t[13]["damping_Ns_per_m"], nlohmann::json({0.5, 0.3}));
  EXPECT_EQ(t[13]["ground_damping_Ns_per_m"], 0.1);
  EXPECT_EQ(t[13]["gravity_m_s2"], nlohmann::json({0.0, -9.81}));
  EXPECT_EQ(t[14]["kind"], "attractor");
  EXPECT_EQ(t[14]["period_s"], 1.5);
  EXPECT_EQ(t[14]["swirl"], 0.3);
  EXPECT_EQ(t[15]["kind"], "friction");
  EXPECT_EQ(t[15]["static_coefficient"], 0.9);
  EXPECT_EQ(t[15]["press_N"], 1.5);
  EXPECT_EQ(t[15]["stick_speed_m_s"], 0.003);
  EXPECT_EQ(t[15]["passive"], true);
  EXPECT_EQ(t[14]["radius_m"], 0.02);
  EXPECT_EQ(t[14]["passive"], false);
}

// A 256 x 256 height field of smooth forces up to about 2 N, as an image texture compiles to.
HeightFieldTerm smooth_field() {
  HeightFieldTerm f;
  f.nx = f.ny = 256;
  f.origin_m[0] = f.origin_m[1] = -0.0128;
  f.spacing_m[0] = f.spacing_m[1] = 1e-4;
  for (std::uint32_t y = 0; y < f.ny; ++y)
    for (std::uint32_t x = 0; x < f.nx; ++x) {
      f.force_x_N.push_back(static_cast<float>(1.9 * std::sin(0.05 * x) * std::cos(0.031 * y)));
      f.force_y_N.push_back(static_cast<float>(-2.1 * std::cos(0.05 * x) * std::sin(0.031 * y) + 1e-5 * x));
    }
  return f;
}

TEST(PatchFormat, CompactGridsKeepEveryForceWithinATenthOfAPercentInHalfTheBytes) {
  const auto program = program_of({smooth_field()});
  CompactReport report;
  const auto full = serialize(program);
  const auto compact = serialize(program, {.compact_grids = true}, &report);
  EXPECT_EQ(report.compacted, 1u);
  EXPECT_EQ(report.kept, 0u);
  EXPECT_GT(report.largest_error, 0.0);  // binary16 is not exact for these values
  EXPECT_LE(report.largest_error, kCompactTolerance);
  EXPECT_LT(compact.size(), full.size() * 52 / 100);
  const auto back = deserialize(compact);
  const auto& a = std::get<HeightFieldTerm>(program.terms[0]);
  const auto& b = std::get<HeightFieldTerm>(back.terms[0]);
  ASSERT_EQ(b.force_x_N.size(), a.force_x_N.size());
  double peak = 0, worst = 0;
  for (std::size_t i = 0; i < a.force_x_N.size(); ++i)
    peak = std::max({peak, std::abs(static_cast<double>(a.force_x_N[i])), std::abs(static_cast<double>(a.force_y_N[i]))});
  for (std::size_t i = 0; i < a.force_x_N.size(); ++i)
    worst = std::max({worst, std::abs(static_cast<double>(b.force_x_N[i]) - a.force_x_N[i]),
                      std::abs(static_cast<double>(b.force_y_N[i]) - a.force_y_N[i])});
  EXPECT_LE(worst / peak, 1e-3);
  EXPECT_DOUBLE_EQ(worst / peak, report.largest_error);
}

TEST(PatchFormat, AGridThatHalvesCannotHoldStaysFloat32) {
  auto field = smooth_field();
  field.force_x_N[0] = 1e6f;  // beyond binary16's largest finite value (65504)
  const auto program = program_of({field});
  CompactReport report;
  const auto bytes = serialize(program, {.compact_grids = true}, &report);
  EXPECT_EQ(report.compacted, 0u);
  EXPECT_EQ(report.kept, 1u);
  EXPECT_EQ(bytes, serialize(program));  // exactly the float32 encoding
}

TEST(PatchFormat, FilesAreReadInPlaceAndCheckedWhole) {
  const auto program = program_of({smooth_field(), sample_grating()});
  const auto dir = std::filesystem::temp_directory_path() / ("patch_read_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "p.patch";
  write_patch_file(file, program);
  const auto bytes = serialize(program);
  {
    std::ifstream in(file, std::ios::binary);
    const std::vector<unsigned char> on_disk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(on_disk, bytes);  // the segmented writer writes what serialize makes
  }
  const auto back = read_patch_file(file);
  ASSERT_EQ(back.terms.size(), 2u);
  EXPECT_TRUE(same(back.terms[0], program.terms[0]));
  // One flipped byte inside a grid: the checksum, summed while reading, refuses the file.
  auto corrupt = bytes;
  corrupt[bytes.size() / 2] ^= 0x40;
  std::ofstream(dir / "bad.patch", std::ios::binary).write(reinterpret_cast<const char*>(corrupt.data()),
                                                            static_cast<std::streamsize>(corrupt.size()));
  try {
    read_patch_file(dir / "bad.patch");
    ADD_FAILURE() << "a corrupted file was read";
  } catch (const PatchFormatError& e) {
    EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what();
  }
  // Truncated: refused by its size before any array is allocated.
  std::ofstream(dir / "short.patch", std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), 1000);
  EXPECT_THROW(read_patch_file(dir / "short.patch"), PatchFormatError);
  // A FIFO would block the reader: refused before it is opened.
  ASSERT_EQ(::mkfifo((dir / "fifo.patch").c_str(), 0600), 0);
  EXPECT_THROW(read_patch_file(dir / "fifo.patch"), PatchFormatError);
  std::filesystem::remove_all(dir);
}

TEST(WorkspaceFormat, ProgramsRoundTripWithEveryPatchAndRefuseCorruption) {
  WorkspaceProgram ws;
  ws.name = "two patches";
  ws.size_m[0] = 0.2;
  ws.size_m[1] = 0.1;
  const double c1[2] = {-0.03, 0.01}, s1[2] = {0.04, 0.02}, c2[2] = {0.02, -0.01}, s2[2] = {0.05, 0.05};
  ws.patches.push_back(place_patch(program_of({smooth_field()}), c1, s1, "images/x.png"));
  ws.patches.push_back(place_patch(program_of({sample_grating(), spring(50.0)}), c2, s2, "corduroy"));
  const auto dir = std::filesystem::temp_directory_path() / ("wsp_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_workspace_program_file(dir / "w.wsp", ws);
  EXPECT_TRUE(looks_like_workspace_program_file(dir / "w.wsp"));
  EXPECT_FALSE(looks_like_patch_file(dir / "w.wsp"));
  const auto back = read_workspace_program_file(dir / "w.wsp");
  EXPECT_EQ(back.name, ws.name);
  EXPECT_EQ(back.size_m[0], 0.2);
  ASSERT_EQ(back.patches.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.patches[i].source, ws.patches[i].source);
    EXPECT_EQ(back.patches[i].centre_m[0], ws.patches[i].centre_m[0]);
    EXPECT_EQ(back.patches[i].size_m[1], ws.patches[i].size_m[1]);
    EXPECT_EQ(serialize(*back.patches[i].program), serialize(*ws.patches[i].program));
  }
  // A flipped byte anywhere in the payload is refused by the checksum.
  std::ifstream in(dir / "w.wsp", std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  bytes[bytes.size() - 40] ^= 0x01;
  std::ofstream(dir / "bad.wsp", std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  EXPECT_THROW(read_workspace_program_file(dir / "bad.wsp"), PatchFormatError);
  bytes.resize(100);
  std::ofstream(dir / "short.wsp", std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  EXPECT_THROW(read_workspace_program_file(dir / "short.wsp"), PatchFormatError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sandpaper::runtime
