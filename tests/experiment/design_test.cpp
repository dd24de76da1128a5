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

TEST(Design, EachDimensionHasAMagnitudeEstimationDesign) {
  for (const char* percept : {"softness", "viscosity", "slipperiness"}) {
    const auto d = load_design(kExamples / (std::string(percept) + "-magnitude.toml"));
    EXPECT_EQ(d.percept, percept);
    EXPECT_EQ(d.task, Task::MagnitudeEstimation);
    EXPECT_EQ(d.stimuli.size(), 9u);
  }
  EXPECT_EQ(load_design(kExamples / "roughness-magnitude.toml").percept, "roughness");
  // Another task cannot scale another percept.
  try {
    parse_design("schema = \"sandpaper-experiment/1\"\ntitle = \"t\"\ntask = \"sorting\"\npercept = \"softness\"\n"
                 "stimuli = [\"spring 20 N/m\", \"spring 40 N/m\", \"spring 80 N/m\"]\ninstructions = \"x\"\n[sorting]\npiles = [2]\n",
                 "bad.toml");
    FAIL() << "accepted";
  } catch (const DesignError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:4:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("magnitude estimation only"), std::string::npos) << e.what();
  }
}

// The subject sees a subject's heading and flowing paragraphs, not the experimenter's title and
// the TOML's hard line breaks.
TEST(Design, TheSubjectSeesASubjectsTitleAndFlowingParagraphs) {
  auto d = load_design(kExamples / "roughness-magnitude.toml");
  EXPECT_NE(d.title.find("Minsky 1995"), std::string::npos);
  EXPECT_EQ(subject_title_of(d), "How rough does each surface feel?");
  EXPECT_EQ(subject_title_of(load_design(kExamples / "softness-magnitude.toml")), "How soft does each surface feel?");
  d.subject_title = "Surfaces";
  EXPECT_EQ(subject_title_of(d), "Surfaces");
  EXPECT_EQ(instruction_paragraphs("\n  One line\nand the next.\n\n\nA second\n   paragraph.  \n"),
            (std::vector<std::string>{"One line and the next.", "A second paragraph."}));
  const auto shipped = instruction_paragraphs(load_design(kExamples / "roughness-magnitude.toml").instructions);
  ASSERT_EQ(shipped.size(), 1u);  // the shipped text has no blank line: one paragraph, its breaks flowing
  EXPECT_EQ(shipped[0].find('\n'), std::string::npos);
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
