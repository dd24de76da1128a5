// calibration::ParsedFileCache: a folder loaded through it is the folder loaded without it, and a
// file whose bytes changed since it was kept is read again, never served from the cache.
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;
const fs::path kShipped = fs::path(SANDPAPER_SOURCE_DIR) / "calibration";

std::size_t toml_files_in(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.path().extension() == ".toml";
  return n;
}

fs::path copy_of_shipped(const std::string& tag) {
  fs::path dir = fs::path(test::temp_dir(tag)) / "calibration";
  fs::copy(kShipped, dir, fs::copy_options::recursive);
  return dir;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture text not found: " << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// What a load gave, as text: every map, level and device with its numbers, and the knowledge files'.
std::string summary(const calibration::CalibrationSet& s) {
  std::ostringstream os;
  os.precision(17);
  for (const auto& m : s.maps())
    os << "map " << m.id << " " << m.file << " " << m.percept << " " << m.slope << " " << m.intercept.value_or(-1) << "\n";
  for (const auto& l : s.roughness_levels()) os << "level " << l.name << " " << l.value << "\n";
  for (const auto& d : s.devices())
    os << "device " << d.name << " " << d.file << " " << d.max_force_N << " " << d.workspace_radius_m << "\n";
  os << "jnd " << s.knowledge().force_jnd.weber_fraction << " groupings "
     << s.knowledge().roughness_groups.groupings.size() << " stimuli " << s.knowledge().roughness_groups.stimuli.size()
     << " low-confidence " << s.knowledge().believability.low_confidence.size() << "\n";
  return os.str();
}

// The bytes of one program compiled on `set` (through the constructor that takes a loaded set).
std::string program_bytes(calibration::CalibrationSet set, const fs::path& dir) {
  compiler::CompileOptions o;
  o.device = "sim";
  o.calibration_dir = dir;
  o.library_dir = fs::path(SANDPAPER_SOURCE_DIR) / "library";
  const compiler::Compiler c(o, std::make_shared<const compiler::Library>(o.library_dir), std::move(set));
  const auto r = c.compile_text("roughness coarse; grating period 2.5 mm; softness 0.4", "<test>");
  EXPECT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  if (!r.ok()) return {};
  const auto bytes = schema::serialize(*r.program);
  return {bytes.begin(), bytes.end()};
}

std::string load_error(const fs::path& dir, calibration::ParsedFileCache* cache) {
  try {
    calibration::CalibrationSet::load(dir, cache);
  } catch (const calibration::CalibrationError& e) {
    return e.what();
  }
  return {};
}

TEST(ParsedFileCache, AFolderLoadedThroughItIsTheFolderLoadedWithout) {
  const auto dir = copy_of_shipped("cache-same");
  const auto plain = calibration::CalibrationSet::load(dir);
  calibration::ParsedFileCache cache;
  const auto learning = calibration::CalibrationSet::load(dir, &cache);
  EXPECT_EQ(cache.size(), toml_files_in(dir));
  EXPECT_EQ(cache.hits(), 0u);
  cache.set_learning(false);
  const auto cached = calibration::CalibrationSet::load(dir, &cache);
  EXPECT_EQ(cache.hits(), toml_files_in(dir)) << "every file should come from the cache on the second load";
  EXPECT_EQ(summary(learning), summary(plain));
  EXPECT_EQ(summary(cached), summary(plain));
  EXPECT_NE(summary(plain).find("device sim"), std::string::npos);
  EXPECT_EQ(program_bytes(cached, dir), program_bytes(plain, dir));
}

TEST(ParsedFileCache, AFileChangedSinceItWasKeptIsReadAgain) {
  const auto dir = copy_of_shipped("cache-changed");
  calibration::ParsedFileCache cache;
  calibration::CalibrationSet::load(dir, &cache);
  cache.set_learning(false);
  const auto sim = dir / "devices" / "sim.toml";
  const std::string shipped = read(sim);

  // One byte different: the new value, not the kept one.
  write(sim, replaced(shipped, "max_continuous = \"10 N\"", "max_continuous = \"12 N\""));
  const auto changed = calibration::CalibrationSet::load(dir, &cache);
  ASSERT_NE(changed.find_device("sim"), nullptr);
  EXPECT_DOUBLE_EQ(changed.find_device("sim")->max_force_N, 12.0);
  EXPECT_EQ(cache.hits(), toml_files_in(dir) - 1);
  EXPECT_EQ(summary(changed), summary(calibration::CalibrationSet::load(dir)));

  // A broken file after it was kept whole: the same messages as a load without the cache.
  write(sim, replaced(shipped, "max_continuous = \"10 N\"", "max_continuous = \"10 m\""));
  const std::string without = load_error(dir, nullptr);
  ASSERT_NE(without.find("sim.toml"), std::string::npos) << without;
  EXPECT_EQ(load_error(dir, &cache), without);

  // Back as shipped: served from the cache again.
  write(sim, shipped);
  const auto before = cache.hits();
  calibration::CalibrationSet::load(dir, &cache);
  EXPECT_EQ(cache.hits() - before, toml_files_in(dir));
}

// The path shown is kept with the file. Run from the folder above the calibration, the folder shows
// its files as "calibration/maps/x.toml" (a path that opens from there); named with a trailing '/'
// it reads the same files but shows them by their absolute paths ("maps/x.toml" would not open), so
// nothing is served, and nothing is counted as served.
TEST(ParsedFileCache, AFileShownUnderAnotherNameIsReadAgain) {
  const auto dir = copy_of_shipped("cache-shown");
  const fs::path slashed = dir.string() + "/";
  const auto cwd = fs::current_path();
  fs::current_path(dir.parent_path());
  struct Back {
    fs::path to;
    ~Back() { fs::current_path(to); }
  } back{cwd};
  calibration::ParsedFileCache cache;
  const auto kept = calibration::CalibrationSet::load(dir, &cache);
  cache.set_learning(false);
  const auto other = calibration::CalibrationSet::load(slashed, &cache);
  EXPECT_EQ(cache.hits(), 0u);
  const auto plain = calibration::CalibrationSet::load(slashed);
  EXPECT_EQ(summary(other), summary(plain));
  ASSERT_NE(plain.find_device("sim"), nullptr);
  ASSERT_NE(kept.find_device("sim"), nullptr);
  EXPECT_NE(plain.find_device("sim")->file, kept.find_device("sim")->file) << "the fixture should show the two loads apart";
}

TEST(ParsedFileCache, ACacheNotLearningKeepsNothing) {
  calibration::ParsedFileCache cache;
  cache.set_learning(false);
  calibration::CalibrationSet::load(kShipped, &cache);
  calibration::CalibrationSet::load(kShipped, &cache);
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_EQ(cache.hits(), 0u);
}

}  // namespace
}  // namespace sandpaper
