// Data that cannot support a fit is refused with a message that says what is missing, at the row
// that shows it (file:line) where there is one. One test per refusal.
#include <string>

#include <gtest/gtest.h>

#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"

using namespace sandpaper::calibration;

namespace {

const std::string kHeader = "subject,stimulus,force_N,period_mm,response\n";
// Three stimuli at three forces, two subjects: enough for a fit.
const std::string kGood = kHeader +
                          "A,s1,0.2,1,2\n"
                          "A,s2,0.8,2,5\n"
                          "A,s3,3.2,5,9\n"
                          "B,s1,0.2,1,20\n"
                          "B,s2,0.8,2,45\n"
                          "B,s3,3.2,5,110\n";

// The FitError of fitting `csv`, which must be refused.
FitError refusal(const std::string& csv) {
  try {
    (void)fit_magnitude_estimation(parse_magnitude_estimation_csv(csv, "r.csv"));
  } catch (const FitError& e) {
    return e;
  }
  ADD_FAILURE() << "not refused:\n" << csv;
  return FitError("", 0, "");
}

FitError device_refusal(const std::string& csv) {
  try {
    (void)fit_device(parse_device_readings_csv(csv, "g.csv"));
  } catch (const FitError& e) {
    return e;
  }
  ADD_FAILURE() << "not refused:\n" << csv;
  return FitError("", 0, "");
}

}  // namespace

TEST(Refusal, GoodDataIsAccepted) {
  const auto f = fit_magnitude_estimation(parse_magnitude_estimation_csv(kGood, "r.csv"));
  EXPECT_EQ(f.force.df_residual, 1);
  EXPECT_EQ(f.stimuli.size(), 3u);
}

TEST(Refusal, MissingColumns) {
  const auto e = refusal("subject,stimulus,force_N,response\nA,s1,0.2,2\n");
  EXPECT_EQ(e.line, 1);
  EXPECT_NE(e.message.find("missing column `period_mm`"), std::string::npos) << e.what();
  EXPECT_NE(e.message.find("subject,stimulus,force_N,period_mm,response"), std::string::npos) << e.what();
  EXPECT_EQ(std::string(e.what()).rfind("r.csv:1: error: ", 0), 0u) << e.what();
}

TEST(Refusal, TooFewStimuli) {
  const auto e = refusal(kHeader + "A,s1,0.2,1,2\nA,s2,0.8,2,5\nB,s1,0.2,1,20\nB,s2,0.8,2,45\n");
  EXPECT_NE(e.message.find("too few stimuli: 2"), std::string::npos) << e.what();
  EXPECT_NE(e.message.find("at least 3"), std::string::npos) << e.what();
}

TEST(Refusal, NonPositiveResponseNamesTheRow) {
  const auto e = refusal(kHeader + "A,s1,0.2,1,2\nA,s2,0.8,2,0\nA,s3,3.2,5,9\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("response is 0"), std::string::npos) << e.what();
  EXPECT_NE(e.message.find("must be positive"), std::string::npos) << e.what();
  EXPECT_EQ(refusal(kHeader + "A,s1,0.2,1,-3\n").line, 2);
}

TEST(Refusal, NonPositiveForceNamesTheRow) {
  const auto e = refusal(kHeader + "A,s1,0.2,1,2\nA,s2,0,2,5\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("force_N is 0"), std::string::npos) << e.what();
  EXPECT_NE(e.message.find("log10"), std::string::npos) << e.what();
}

TEST(Refusal, NonPositivePeriodNamesTheRow) {
  const auto e = refusal(kHeader + "A,s1,0.2,-1,2\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("period_mm is -1"), std::string::npos) << e.what();
}

TEST(Refusal, NotANumber) {
  const auto e = refusal(kHeader + "A,s1,0.2,1,2\nA,s2,0.8,2,lots\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("`response` is `lots`, not a number"), std::string::npos) << e.what();
  EXPECT_NE(refusal(kHeader + "A,s1,inf,1,2\n").message.find("not a finite number"), std::string::npos);
}

TEST(Refusal, OneForceLevel) {
  const auto e = refusal(kHeader + "A,s1,0.5,1,2\nA,s2,0.5,2,3\nA,s3,0.5,5,4\n");
  EXPECT_NE(e.message.find("only one force level (0.5 N)"), std::string::npos) << e.what();
}

TEST(Refusal, SubjectWithNoUsableResponses) {
  const auto e = refusal(kGood + "C,s1,0.2,1,\nC,s2,0.8,2,NA\n");
  EXPECT_EQ(e.line, 8);
  EXPECT_NE(e.message.find("subject `C` has no usable responses"), std::string::npos) << e.what();
}

TEST(Refusal, StimulusNoOneAnswered) {
  const auto e = refusal(kGood + "A,s4,1.6,3,\nB,s4,1.6,3,\n");
  EXPECT_EQ(e.line, 8);
  EXPECT_NE(e.message.find("stimulus `s4` has no answered trial"), std::string::npos) << e.what();
}

TEST(Refusal, StimulusWithTwoForces) {
  const auto e = refusal(kGood + "C,s2,0.9,2,4\n");
  EXPECT_EQ(e.line, 8);
  EXPECT_NE(e.message.find("stimulus `s2` is 0.9 N, 2 mm here but 0.8 N, 2 mm on line 3"), std::string::npos) << e.what();
}

TEST(Refusal, NoTrials) {
  const auto e = refusal(kHeader);
  EXPECT_NE(e.message.find("no trials"), std::string::npos) << e.what();
}

TEST(Refusal, MeansExactlyOnALine) {
  // Estimates made by a formula: R = 10 F^0.5 exactly.
  const auto e = refusal(kHeader + "A,s1,1,1,10\nA,s2,4,2,20\nA,s3,16,5,40\n");
  EXPECT_NE(e.message.find("exactly on a line"), std::string::npos) << e.what();
}

TEST(Refusal, WrongNumberOfFields) {
  const auto e = refusal(kHeader + "A,s1,0.2,1,2\nA,s2,0.8,2\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("4 fields, but the header (line 1) has 5 columns"), std::string::npos) << e.what();
}

TEST(Refusal, DeviceTooFewReadings) {
  const auto e = device_refusal("command,force_N\n0,0.01\n1000,0.9\n");
  EXPECT_NE(e.message.find("too few readings for the readings: 2"), std::string::npos) << e.what();
  EXPECT_NE(e.message.find("at least 3"), std::string::npos) << e.what();
  const auto ey = device_refusal("command,force_N,axis\n0,0,x\n500,0.4,x\n1000,0.9,x\n0,0,y\n1000,0.9,y\n");
  EXPECT_NE(ey.message.find("too few readings for axis y: 2"), std::string::npos) << ey.what();
}

TEST(Refusal, DeviceOneCommandLevel) {
  const auto e = device_refusal("command,force_N\n1000,0.85\n1000,0.86\n1000,0.84\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("one command level (1000) only"), std::string::npos) << e.what();
}

TEST(Refusal, DeviceNonFiniteValue) {
  const auto e = device_refusal("command,force_N\n0,0\n1000,nan\n2000,1.7\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("not a finite number"), std::string::npos) << e.what();
}

TEST(Refusal, DeviceNegativeGain) {
  const auto e = device_refusal("command,force_N\n0,0\n1000,-0.85\n2000,-1.7\n3000,-2.6\n");
  EXPECT_NE(e.message.find("force does not grow with the command"), std::string::npos) << e.what();
}

TEST(Refusal, DeviceBadAxis) {
  const auto e = device_refusal("command,force_N,axis\n0,0,x\n1000,0.85,z\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("axis is `z`; it must be x or y"), std::string::npos) << e.what();
}

TEST(Refusal, DeviceMissingColumn) {
  const auto e = device_refusal("command,newtons\n0,0\n");
  EXPECT_NE(e.message.find("missing column `force_N`"), std::string::npos) << e.what();
}

// A gauge reading of 7.5e300 N was taken: the fit's sums of squares overflowed and `calibrate device`
// printed a gain of 1.4e296 N per unit with s.e. inf and R^2 nan, exit 0 (docs/RELIABILITY.md, F27).
TEST(Refusal, DeviceReadingPast1e12) {
  const auto e = device_refusal("command,force_N\n0,0.02\n1000,0.86\n2000,7.541e300\n3000,2.59\n");
  EXPECT_EQ(e.line, 4);
  EXPECT_NE(e.message.find("`force_N` is `7.541e300`: a number here is 0, or 1e-12 to 1e12 in magnitude"), std::string::npos)
      << e.what();
  EXPECT_NE(device_refusal("command,force_N\n0,0\n-2e12,0.9\n2000,1.7\n").message.find("`command` is `-2e12`"),
            std::string::npos);
}

// Three subjects, one trial each: each estimate divided by its subject's geometric mean (itself)
// left every mean estimate equal, and the fit was rounding noise (R^2 -300 %, F -0.75) written into
// a map the map loader refuses (docs/RELIABILITY.md, F28). A subject who answered fewer than two
// stimuli is refused when estimates are normalised.
TEST(Refusal, SubjectWhoAnsweredOneStimulusOnly) {
  const auto e = refusal(kHeader + "S00,a9p19,0.673984,0.9,3.06\nS0,a4p,1,2.5,0.602\nS01,a10p9,0.327364,0.9,1.80\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("subject `S00` answered one stimulus only (`a9p19`)"), std::string::npos) << e.what();
  // The same trials without normalisation are raw estimates, and fit.
  EXPECT_NO_THROW((void)fit_magnitude_estimation(
      parse_magnitude_estimation_csv(kHeader + "S00,a9p19,0.673984,0.9,3.06\nS0,a4p,1,2.5,0.602\nS01,a10p9,0.327364,0.9,1.80\n", "r.csv"),
      Normalisation::None));
}

// A force of 1.7e-310 N (subnormal): `calibrate fit -o` wrote the map's domain through std::stod,
// which throws on a subnormal: exit 3, "internal error: stod" (docs/RELIABILITY.md, F31). A number
// in these files is 0, or 1e-12 to 1e12 in magnitude, as a quantity in the language.
TEST(Refusal, ForceBelow1eMinus12) {
  const auto e = refusal(kHeader + "A,s1,1.73311e-310,1,2\nA,s2,0.8,2,5\nA,s3,3.2,5,9\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("`force_N` is `1.73311e-310`: a number here is 0, or 1e-12 to 1e12"), std::string::npos)
      << e.what();
  EXPECT_NO_THROW((void)fit_magnitude_estimation(parse_magnitude_estimation_csv(
      kHeader + "A,s1,1e-12,1,2\nA,s2,0.8,2,5\nA,s3,3.2,5,9\nB,s1,1e-12,1,20\nB,s2,0.8,2,45\nB,s3,3.2,5,110\n", "r.csv")));
}

// One subject giving 2.5 to every stimulus: the mean estimates were all equal, the fit a slope of
// exactly 0 with a residual of rounding noise, and `calibrate fit -o` wrote it as a map the loader
// refuses ("a compile map's slope must not be zero"; docs/RELIABILITY.md, F32). So for a gauge
// reading one force at every command.
TEST(Refusal, MeanEstimatesThatDoNotVary) {
  const auto e = refusal(kHeader + "A,s1,0.2,1,2.5\nA,s2,0.8,2,2.5\nA,s3,3.2,5,2.5\nA,s4,1.6,3,2.5\nA,s2,0.8,2,2.5\n");
  EXPECT_NE(e.message.find("every stimulus has the same mean estimate (2.5)"), std::string::npos) << e.what();
  const auto g = device_refusal("command,force_N\n0,5\n1000,5\n2000,5\n3000,5\n");
  EXPECT_NE(g.message.find("reads the same force (5 N) at every command"), std::string::npos) << g.what();
}

