// Experiment design files (schema/files/experiment.schema.json): the shipped examples read, and a
// bad design lists every problem at its line and column before anything runs.
#include <gtest/gtest.h>

#include <filesystem>

#include "sandpaper/experiment/design.hpp"

namespace sandpaper::experiment {
namespace {

const std::filesystem::path kExamples = std::filesystem::path(SANDPAPER_SOURCE_DIR) / "examples/experiments";

TEST(Design, ShippedExamplesRead) {
  const auto d = load_design(kExamples / "roughness-magnitude.toml");
  EXPECT_EQ(d.task, Task::MagnitudeEstimation);
  EXPECT_EQ(d.stimuli.size(), 12u);
  EXPECT_EQ(d.stimuli.front().text, "a1p7");
  EXPECT_EQ(d.repetitions, 3);
  EXPECT_EQ(d.seed, 1995u);
  EXPECT_EQ(d.practice, 4);
  EXPECT_DOUBLE_EQ(d.duration_s, 3.0);
  EXPECT_DOUBLE_EQ(d.ramp_s, 0.25);
  EXPECT_DOUBLE_EQ(d.hand_speed_m_s, 0.03);
  EXPECT_DOUBLE_EQ(d.hand_amplitude_m, 0.02);
  EXPECT_EQ(d.checksum, design_checksum(d.text));
  EXPECT_EQ(load_design(kExamples / "roughness-sorting.toml").piles, (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(load_design(kExamples / "force-jnd.toml").increments.size(), 7u);
  EXPECT_EQ(load_design(kExamples / "texture-confidence.toml").task, Task::Confidence);
}

TEST(Design, ChecksumTellsDesignsApart) {
  EXPECT_EQ(design_checksum("a"), design_checksum("a"));
  EXPECT_NE(design_checksum("a"), design_checksum("b"));
  EXPECT_EQ(design_checksum(""), "fnv1a64:cbf29ce484222325");  // FNV-1a's offset basis: nothing hashed
}

std::string problems_of(const std::string& text) {
  try {
    parse_design(text, "bad.toml");
  } catch (const DesignError& e) {
    return e.what();
  }
  return "";
}

TEST(Design, EveryProblemListedAtItsPlace) {
  const std::string text =
      "schema = \"sandpaper-experiment/1\"\n"
      "title = \"t\"\n"
      "task = \"sorting\"\n"
      "stimuli = [\"a3p7\", \"a3p7\", \"missing.hmat\"]\n"
      "instructions = \"i\"\n"
      "[two_interval]\n"
      "increments = [0.1, 0.2]\n";
  const auto p = problems_of(text);
  EXPECT_NE(p.find("bad.toml:4:20: error: stimulus `a3p7` is listed twice"), std::string::npos) << p;
  EXPECT_NE(p.find("bad.toml:4:28: error: material file `missing.hmat` not found"), std::string::npos) << p;
  EXPECT_NE(p.find("needs a [sorting] table"), std::string::npos) << p;
  EXPECT_NE(p.find("bad.toml:6:1: error: [two_interval] is for task = \"two-interval\""), std::string::npos) << p;
}

TEST(Design, SchemaViolationsNameTheKey) {
  const auto p = problems_of("schema = \"sandpaper-experiment/1\"\ntitle = \"t\"\ntask = \"guessing\"\nstimuli = []\n"
                             "instructions = \"i\"\nrepetitions = 0\n");
  EXPECT_NE(p.find("bad.toml:3:8: error: `task`"), std::string::npos) << p;
  EXPECT_NE(p.find("`stimuli`"), std::string::npos) << p;
  EXPECT_NE(p.find("`repetitions`"), std::string::npos) << p;
  EXPECT_NE(problems_of("title = [").find("bad.toml:1:"), std::string::npos);
}

TEST(Design, TwoIntervalTakesOneStandard) {
  const auto p = problems_of("schema = \"sandpaper-experiment/1\"\ntitle = \"t\"\ntask = \"two-interval\"\n"
                             "stimuli = [\"a3p7\", \"a10p7\"]\ninstructions = \"i\"\n[two_interval]\nincrements = [0.1, 0.2]\n");
  EXPECT_NE(p.find("give exactly one stimulus"), std::string::npos) << p;
}

}  // namespace
}  // namespace sandpaper::experiment
