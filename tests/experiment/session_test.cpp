// A session: a device fault mid-trial stops it with the trial marked interrupted (never answered),
// resume continues from that trial in the same order, and a bad stimulus list is refused whole
// before the first trial.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "sandpaper/experiment/observer.hpp"
#include "sandpaper/experiment/presenter.hpp"
#include "sandpaper/experiment/session.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "test_support.hpp"

namespace sandpaper::experiment {
namespace {

const char* kDesign =
    "schema = \"sandpaper-experiment/1\"\ntitle = \"t\"\ntask = \"magnitude-estimation\"\n"
    "stimuli = [\"a3p7\", \"a10p12\", \"a19p100\"]\nrepetitions = 2\nseed = 5\npractice = 1\ninstructions = \"i\"\n"
    "[presentation]\nduration = \"0.2 s\"\nramp = \"0.05 s\"\nhand_speed_mm_s = 30\n";

// Presents on the virtual clock, but reports the loop stopped on presentation `fail_at`.
class FaultyPresenter final : public Presenter {
 public:
  FaultyPresenter(int fail_at, PresentOptions o, std::string cause = "device_unplugged")
      : inner_(runtime::HandScript{runtime::HandPath::Scan, 0.03, 0.02, 0}, o),
        fail_at_(fail_at), cause_(std::move(cause)) {}
  Presentation present(std::shared_ptr<const schema::PatchProgram> program, double gain) override {
    if (count_++ == fail_at_) return {0, true, cause_};
    return inner_.present(std::move(program), gain);
  }
  std::string describe() const override { return "faulty"; }

 private:
  VirtualPresenter inner_;
  int fail_at_, count_ = 0;
  std::string cause_;
};

PresentOptions options(const Design& d) { return {d.rate_hz, d.ramp_s, d.duration_s}; }

TEST(Session, FaultMarksTheTrialInterruptedAndResumeContinuesThere) {
  const auto dir = std::filesystem::path(test::temp_dir("session")) / "S01";
  const auto d = parse_design(kDesign, "d.toml");
  const auto stimuli = prepare_stimuli(d, test::shipped_compiler());
  const auto schedule = make_schedule(d, "S01");
  ASSERT_EQ(schedule.size(), 7u);
  ResultsHeader h;
  h.design_checksum = d.checksum;
  h.subject = "S01";
  h.task = "magnitude-estimation";
  h.trials = 7;
  std::ostringstream log;
  {
    auto writer = ResultsWriter::create(dir, d, h);
    FaultyPresenter presenter(4, options(d));
    auto observer = make_simulated_observer(parse_simulated_observer("simulated:seed=1"), "S01");
    const auto out = run_session(d, stimuli, schedule, 0, presenter, *observer, writer, log);
    EXPECT_TRUE(out.interrupted);
    EXPECT_EQ(out.cause, "device_unplugged");
    EXPECT_EQ(out.answered, 4);
    EXPECT_EQ(out.next_trial, 4);
  }
  auto r = read_results(dir);
  ASSERT_EQ(r.answers.size(), 4u);
  ASSERT_EQ(r.interruptions.size(), 1u);
  EXPECT_EQ(r.interruptions[0].trial, 4);
  EXPECT_EQ(r.next_trial(), 4);
  EXPECT_NE(log.str().find("trial 5 of 7 interrupted"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("Fix the device, then"), std::string::npos) << log.str();
  {
    auto writer = ResultsWriter::reopen(dir);
    VirtualPresenter presenter(runtime::HandScript{runtime::HandPath::Scan, 0.03, 0.02, 0},
                               options(d));
    auto observer = make_simulated_observer(parse_simulated_observer("simulated:seed=1"), "S01");
    const auto out = run_session(d, stimuli, schedule, r.next_trial(), presenter, *observer, writer, log);
    EXPECT_TRUE(out.finished);
    EXPECT_EQ(out.answered, 3);
  }
  r = read_results(dir);
  ASSERT_EQ(r.answers.size(), 7u);
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(r.answers[i].trial, static_cast<int>(i));
    EXPECT_EQ(r.answers[i].stimuli.at(0), d.stimuli[static_cast<std::size_t>(schedule[i].stimuli[0])].text);
    // The ramped presentation reached the compiled force (within the scan's sampling).
    EXPECT_NEAR(r.answers[i].felt_force_N[0], r.answers[i].compiled_force_N[0], 0.03 * r.answers[i].compiled_force_N[0]);
  }
}

// Ctrl-C during a presentation stops the loop as asked: nothing is wrong with the device, so the
// session does not tell the experimenter to fix it.
TEST(Session, AStopAskedForDoesNotBlameTheDevice) {
  const auto dir = std::filesystem::path(test::temp_dir("session-ctrl-c")) / "S01";
  const auto d = parse_design(kDesign, "d.toml");
  const auto stimuli = prepare_stimuli(d, test::shipped_compiler());
  const auto schedule = make_schedule(d, "S01");
  ResultsHeader h;
  h.design_checksum = d.checksum;
  h.subject = "S01";
  h.task = "magnitude-estimation";
  h.trials = static_cast<int>(schedule.size());
  auto writer = ResultsWriter::create(dir, d, h);
  FaultyPresenter presenter(2, options(d), "stop_requested");
  auto observer = make_simulated_observer(parse_simulated_observer("simulated:seed=1"), "S01");
  std::ostringstream log;
  const auto out = run_session(d, stimuli, schedule, 0, presenter, *observer, writer, log);
  EXPECT_TRUE(out.interrupted);
  EXPECT_NE(log.str().find("trial 3 of 7 interrupted: stopped as asked"), std::string::npos) << log.str();
  EXPECT_EQ(log.str().find("Fix the device"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("`sandpaper experiment resume` continues"), std::string::npos) << log.str();
}

TEST(Session, TheSubjectCanStopAtTheTerminal) {
  const auto dir = std::filesystem::path(test::temp_dir("session-stop")) / "S01";
  const auto d = parse_design(kDesign, "d.toml");
  const auto stimuli = prepare_stimuli(d, test::shipped_compiler());
  const auto schedule = make_schedule(d, "S01");
  ResultsHeader h;
  h.design_checksum = d.checksum;
  h.subject = "S01";
  h.trials = 7;
  auto writer = ResultsWriter::create(dir, d, h);
  VirtualPresenter presenter(runtime::HandScript{}, options(d));
  std::istringstream answers("\n3\nrough\n5\nq\n");  // Enter for the instructions, a bad answer re-asked
  std::ostringstream prompts, log;
  auto observer = make_terminal_observer(answers, prompts);
  const auto out = run_session(d, stimuli, schedule, 0, presenter, *observer, writer, log);
  EXPECT_TRUE(out.stopped);
  EXPECT_EQ(out.answered, 2);
  EXPECT_NE(prompts.str().find("Please type a positive number"), std::string::npos) << prompts.str();
  const auto r = read_results(dir);
  ASSERT_EQ(r.answers.size(), 2u);
  EXPECT_EQ(*r.answers[0].response, 3);
  EXPECT_EQ(*r.answers[1].response, 5);
}

TEST(Session, BadStimuliAreAllRefusedBeforeTheFirstTrial) {
  const auto d = parse_design(
      "schema = \"sandpaper-experiment/1\"\ntitle = \"t\"\ntask = \"magnitude-estimation\"\n"
      "stimuli = [\"a3p7\", \"corduroyy\", \"a1p100\", \"spring 200 N/m\", \"a10p7\"]\ninstructions = \"i\"\n",
      "d.toml");
  try {
    prepare_stimuli(d, test::shipped_compiler());
    FAIL() << "no error";
  } catch (const DesignError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("d.toml:4:20: error: stimulus `corduroyy` does not compile"), std::string::npos) << w;
    EXPECT_NE(w.find("stimulus `a1p100` lies in the low-confidence region"), std::string::npos) << w;
    EXPECT_NE(w.find("stimulus `spring 200 N/m` has no texture force"), std::string::npos) << w;
    EXPECT_EQ(w.find("`a3p7`"), std::string::npos) << w;
  }
}

}  // namespace
}  // namespace sandpaper::experiment
