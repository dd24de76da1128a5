// The whole loop without people (issue 13's acceptance): simulated observers on the simulated
// joystick, on the virtual clock, through the same schedule, presenter, results folders and
// analysis a person's session uses. What the analysis recovers is compared with what the
// observers were told.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "sandpaper/experiment/analysis.hpp"
#include "sandpaper/experiment/observer.hpp"
#include "sandpaper/experiment/presenter.hpp"
#include "sandpaper/experiment/session.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "test_support.hpp"

namespace sandpaper::experiment {
namespace {

const std::filesystem::path kExamples = std::filesystem::path(SANDPAPER_SOURCE_DIR) / "examples/experiments";

// Runs `subjects` simulated subjects through `d` into <dir>/S01 ... and returns `dir`.
std::filesystem::path study(const Design& d, const std::string& observer, int subjects, const std::string& tag) {
  const std::filesystem::path dir = test::temp_dir(tag);
  const auto stimuli = prepare_stimuli(d, test::shipped_compiler());
  const PresentOptions po{d.rate_hz, d.ramp_s, d.duration_s};
  runtime::HandScript hand;
  hand.speed_m_s = d.hand_speed_m_s;
  hand.amplitude_m = d.hand_amplitude_m;
  for (int s = 1; s <= subjects; ++s) {
    const std::string subject = "S0" + std::to_string(s);
    const auto schedule = make_schedule(d, subject);
    ResultsHeader h;
    h.design_checksum = d.checksum;
    h.subject = subject;
    h.task = task_name(d.task);
    h.device = d.device;
    h.percept = d.percept;
    h.trials = static_cast<int>(schedule.size());
    auto writer = ResultsWriter::create(dir / subject, d, h);
    VirtualPresenter presenter(hand, po);
    auto obs = make_simulated_observer(parse_simulated_observer(observer), subject);
    std::ostringstream log;
    const auto out = run_session(d, stimuli, schedule, 0, presenter, *obs, writer, log);
    EXPECT_TRUE(out.finished) << log.str();
  }
  return dir;
}

TEST(SimulatedStudy, MagnitudeEstimationRecoversTheExponent) {
  const auto d = load_design(kExamples / "roughness-magnitude.toml");  // Table 8, 3 repetitions
  for (double exponent : {0.76, 0.5}) {
    const auto dir = study(d, "simulated:exponent=" + std::to_string(exponent) + ",noise=0.15,seed=3", 8,
                           "study-me-" + std::to_string(exponent));
    const auto a = analyse(dir, {});
    const auto& m = a.report["magnitude_estimation"];
    const double slope = m["slope"], se = m["slope_se"];
    EXPECT_LT(std::abs(slope - exponent), 2 * se) << "exponent " << exponent << ": slope " << slope << " +- " << se;
    EXPECT_GT(se, 0);
    EXPECT_EQ(m["n_trials"], 8 * 36);
    EXPECT_EQ(m["subjects"].size(), 8u);
    for (const char* key : {"slope", "slope_se", "intercept", "intercept_se", "r2", "r2_adj", "s", "df", "f"})
      EXPECT_TRUE(m.contains(key)) << key;
    EXPECT_TRUE(std::filesystem::exists(dir / "analysis" / "magnitude-estimation.svg"));
  }
}

// Each perceptual dimension's example design, six simulated subjects, exponents of either sign and
// of sizes the literature gives (softness -0.8 from squeezed rubber; viscosity 0.42 from stirred
// fluids; slipperiness -1, Ekman et al.'s bound) and others: the fit on the stimuli's physical
// quantity (stiffness, damping, friction coefficient) recovers each within two standard errors.
TEST(SimulatedStudy, EachDimensionsDesignRecoversTheObserversExponent) {
  struct Case {
    const char* design;
    const char* predictor;
    double exponent;
  };
  for (const Case& c : {Case{"softness-magnitude.toml", "stiffness", -0.8}, Case{"softness-magnitude.toml", "stiffness", -0.5},
                        Case{"viscosity-magnitude.toml", "damping", 0.42}, Case{"viscosity-magnitude.toml", "damping", 0.86},
                        Case{"slipperiness-magnitude.toml", "friction", -1.0},
                        Case{"slipperiness-magnitude.toml", "friction", -1.5}}) {
    const auto d = load_design(kExamples / c.design);
    const auto dir = study(d, "simulated:exponent=" + std::to_string(c.exponent) + ",noise=0.15,seed=5", 6,
                           std::string("study-dim-") + c.predictor + std::to_string(c.exponent));
    const auto a = analyse(dir, {});
    const auto& m = a.report["magnitude_estimation"];
    const double slope = m["slope"], se = m["slope_se"];
    EXPECT_EQ(m["percept"], d.percept);
    EXPECT_EQ(m["predictor"], c.predictor);
    EXPECT_GT(se, 0);
    EXPECT_LT(std::abs(slope - c.exponent), 2 * se) << c.design << " exponent " << c.exponent << ": slope " << slope << " +- " << se;
    EXPECT_EQ(m["subjects"].size(), 6u);
    ASSERT_EQ(m["stimuli"].size(), d.stimuli.size());
    // The regression is on the quantity the stimulus text states, not on a force.
    EXPECT_FALSE(m["stimuli"][0].contains("force_N"));
    EXPECT_TRUE(m["stimuli"][0].contains(c.predictor));
  }
}

TEST(SimulatedStudy, SortingFindsThePlantedGroups) {
  // Two groups planted far apart in force and period; the simulated observer sorts by distance in
  // (log force, log period), so the top split of the dendrogram must separate them.
  const auto d = parse_design(
      "schema = \"sandpaper-experiment/1\"\ntitle = \"planted\"\ntask = \"sorting\"\n"
      "stimuli = [\"a1p7\", \"a19p100\", \"a2p7\", \"a10p100\", \"a1p12\", \"a19p50\", \"a2p12\", \"a10p50\"]\n"
      "instructions = \"i\"\nseed = 11\n[sorting]\npiles = [2, 3, 4]\n[presentation]\nduration = \"0.5 s\"\n"
      "ramp = \"0.05 s\"\nhand_speed_mm_s = 30\n",
      "planted.toml");
  const auto dir = study(d, "simulated:noise=0.15,seed=2", 6, "study-sort");
  const auto a = analyse(dir, {});
  const auto& s = a.report["sorting"];
  for (const char* linkage : {"single", "average"}) {
    auto c0 = s[linkage]["clusters"][0].get<std::vector<std::string>>();
    auto c1 = s[linkage]["clusters"][1].get<std::vector<std::string>>();
    std::sort(c0.begin(), c0.end());
    std::sort(c1.begin(), c1.end());
    const std::vector<std::string> weak{"a1p12", "a1p7", "a2p12", "a2p7"}, strong{"a10p100", "a10p50", "a19p100", "a19p50"};
    EXPECT_TRUE((c0 == weak && c1 == strong) || (c0 == strong && c1 == weak)) << linkage << ": " << s[linkage]["clusters"];
  }
  EXPECT_EQ(s["sorts"], 18);
  EXPECT_TRUE(std::filesystem::exists(s["dendrogram"].get<std::string>()));
}

TEST(SimulatedStudy, TwoIntervalRecoversTheWeberFraction) {
  const auto d = load_design(kExamples / "force-jnd.toml");
  const auto dir = study(d, "simulated:weber=0.12,seed=4", 4, "study-2ifc");
  const auto a = analyse(dir, {});
  const auto& t = a.report["two_interval"];
  const double w = t["weber_fraction"], lo = t["weber_fraction_interval"][0], hi = t["weber_fraction_interval"][1];
  EXPECT_LT(lo, 0.12) << w;
  EXPECT_GT(hi, 0.12) << w;
  EXPECT_LT(hi - lo, 0.1);
}

TEST(SimulatedStudy, PoolingDifferentDesignsIsRefusedUnlessAsked) {
  auto d = load_design(kExamples / "roughness-magnitude.toml");
  const auto dir = study(d, "simulated:seed=1", 2, "study-mixed");
  d.text += "\n# edited\n";
  d.checksum = design_checksum(d.text);
  const auto other = study(d, "simulated:seed=1", 1, "study-mixed-other");
  std::filesystem::rename(other / "S01", dir / "S09");
  try {
    analyse(dir, {});
    FAIL() << "pooled";
  } catch (const DesignError& e) {
    EXPECT_NE(std::string(e.what()).find("different designs"), std::string::npos) << e.what();
  }
  AnalyseOptions allow;
  allow.allow_mixed_designs = true;
  EXPECT_EQ(analyse(dir, allow).report["runs"].size(), 3u);
}

}  // namespace
}  // namespace sandpaper::experiment
