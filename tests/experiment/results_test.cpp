// Results folders: every record on disk before the next trial, a torn last line (a kill -9 while
// writing) ignored and cut off on resume, a changed design refused.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>

#include <nlohmann/json.hpp>

#include "sandpaper/experiment/results.hpp"
#include "test_support.hpp"

namespace sandpaper::experiment {
namespace {

const char* kDesign =
    "schema = \"sandpaper-experiment/1\"\ntitle = \"t\"\ntask = \"magnitude-estimation\"\n"
    "stimuli = [\"a3p7\", \"a10p7\", \"a19p100\"]\ninstructions = \"i\"\n";

Answer answer(int trial, double response) {
  Answer a;
  a.trial = trial;
  a.stimuli = {"a3p7"};
  a.compiled_force_N = {0.5777};
  a.felt_force_N = {0.5636};
  a.period_m = {0.0007};
  a.response = response;
  return a;
}

ResultsHeader header(const Design& d) {
  ResultsHeader h;
  h.design_checksum = d.checksum;
  h.subject = "S01";
  h.task = "magnitude-estimation";
  h.device = "sim";
  h.trials = 3;
  return h;
}

TEST(Results, AppendsAndReadsBack) {
  const auto dir = std::filesystem::path(test::temp_dir("results")) / "S01";
  const auto d = parse_design(kDesign, "d.toml");
  {
    auto w = ResultsWriter::create(dir, d, header(d));
    w.append(to_json(answer(0, 4.5)));
    w.append(to_json(answer(1, 7)));
  }
  const auto r = read_results(dir);
  EXPECT_EQ(r.header.subject, "S01");
  EXPECT_EQ(r.design_text, kDesign);
  ASSERT_EQ(r.answers.size(), 2u);
  EXPECT_EQ(*r.answers[1].response, 7);
  EXPECT_DOUBLE_EQ(r.answers[0].felt_force_N.at(0), 0.5636);
  EXPECT_EQ(r.next_trial(), 2);
  // A second `run` into the same folder is refused; nothing is overwritten.
  EXPECT_THROW(ResultsWriter::create(dir, d, header(d)), DesignError);
  EXPECT_EQ(read_results(dir).answers.size(), 2u);
}

TEST(Results, TornLastLineIsTheTrialInProgress) {
  const auto dir = std::filesystem::path(test::temp_dir("results-torn")) / "S01";
  const auto d = parse_design(kDesign, "d.toml");
  { auto w = ResultsWriter::create(dir, d, header(d)); w.append(to_json(answer(0, 4.5))); }
  {
    std::ofstream out(dir / "results.jsonl", std::ios::app);
    out << R"({"record":"answer","trial":1,"stimu)";  // killed mid-write
  }
  EXPECT_EQ(read_results(dir).answers.size(), 1u);
  EXPECT_EQ(read_results(dir).next_trial(), 1);
  {
    auto w = ResultsWriter::reopen(dir);
    w.append(to_json(answer(1, 9)));
  }
  const auto r = read_results(dir);
  ASSERT_EQ(r.answers.size(), 2u);
  EXPECT_EQ(*r.answers[1].response, 9);
}

TEST(Results, MalformedMiddleLineIsAnErrorAtItsLine) {
  const auto dir = std::filesystem::path(test::temp_dir("results-bad")) / "S01";
  const auto d = parse_design(kDesign, "d.toml");
  { auto w = ResultsWriter::create(dir, d, header(d)); w.append({{"record", "answer"}, {"trial", "x"}}); w.append(to_json(answer(0, 1))); }
  try {
    read_results(dir);
    FAIL() << "no error";
  } catch (const DesignError& e) {
    EXPECT_NE(std::string(e.what()).find("results.jsonl:2:1: error: malformed record"), std::string::npos) << e.what();
  }
}

// A number where the file holds a whole number: 1.5, or one beyond an int, is a malformed record
// at its line. nlohmann's get<int> of 2.2e9 is undefined behaviour (fuzz finding F4, issue 16).
TEST(Results, NonWholeOrOutOfRangeCountsAreMalformedRecords) {
  const auto d = parse_design(kDesign, "d.toml");
  int case_index = 0;
  for (const nlohmann::json& bad : {nlohmann::json(2222222221.6), nlohmann::json(1.5), nlohmann::json(2.2e100),
                                    nlohmann::json(std::int64_t{4'000'000'000})}) {
    const auto dir = std::filesystem::path(test::temp_dir("results-whole")) / ("S" + std::to_string(case_index++));
    {
      auto w = ResultsWriter::create(dir, d, header(d));
      auto a = to_json(answer(0, 1));
      a["repetition"] = bad;
      w.append(a);
      w.append(to_json(answer(1, 1)));
    }
    try {
      read_results(dir);
      ADD_FAILURE() << bad.dump() << " was read as a repetition count";
    } catch (const DesignError& e) {
      EXPECT_NE(std::string(e.what()).find("results.jsonl:2:1: error: malformed record: `repetition` must be a whole number"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(Results, BytesThatAreNotUtf8DoNotLoseTheRecord) {
  const auto dir = std::filesystem::path(test::temp_dir("results-utf8")) / "S01";
  const auto d = parse_design(kDesign, "d.toml");
  auto h = header(d);
  h.subject = "S\xff" "1";  // a subject id typed in Latin-1
  { auto w = ResultsWriter::create(dir, d, h); w.append(to_json(answer(0, 2))); }
  const auto r = read_results(dir);
  EXPECT_EQ(r.header.subject, "S\xef\xbf\xbd" "1");  // U+FFFD in UTF-8
  EXPECT_EQ(r.answers.size(), 1u);
}

TEST(Results, ChangedDesignIsRefused) {
  const auto dir = std::filesystem::path(test::temp_dir("results-changed")) / "S01";
  const auto d = parse_design(kDesign, "d.toml");
  { auto w = ResultsWriter::create(dir, d, header(d)); }
  std::ofstream(dir / "design.toml", std::ios::app) << "repetitions = 2\n";
  try {
    read_results(dir);
    FAIL() << "no error";
  } catch (const DesignError& e) {
    EXPECT_NE(std::string(e.what()).find("the design was changed after the run started"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sandpaper::experiment
