// The small CSV reader: quotes, comments, any column order, and errors at the right line.
#include <gtest/gtest.h>

#include "sandpaper/calibration/csv.hpp"
#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"

using namespace sandpaper::calibration;

TEST(Csv, QuotesCommentsAndBlankLines) {
  const auto t = parse_csv("# made by hand\n\n a , \"b, c\" ,d\r\n1,\"say \"\"hi\"\"\", 3 \n# note\n\n4,,6", "t.csv");
  EXPECT_EQ(t.header_line, 3);
  ASSERT_EQ(t.columns.size(), 3u);
  EXPECT_EQ(t.columns[1], "b, c");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0].line, 4);
  EXPECT_EQ(t.rows[0].fields[1], "say \"hi\"");
  EXPECT_EQ(t.rows[0].fields[2], "3");
  EXPECT_EQ(t.rows[1].line, 7);
  EXPECT_EQ(t.rows[1].fields[1], "");
  EXPECT_EQ(*t.column("d"), 2u);
  EXPECT_FALSE(t.column("e"));
}

TEST(Csv, ErrorsCarryTheLine) {
  try {
    parse_csv("a,b\n1,2\n3,\"open\n", "t.csv");
    FAIL();
  } catch (const FitError& e) {
    EXPECT_EQ(e.line, 3);
    EXPECT_EQ(std::string(e.what()).rfind("t.csv:3: error: unterminated quoted field", 0), 0u) << e.what();
  }
  EXPECT_THROW(parse_csv("a,a\n", "t.csv"), FitError);
  EXPECT_THROW(parse_csv("# nothing\n", "t.csv"), FitError);
  EXPECT_THROW(parse_csv("a,b\n1,x\"y\n", "t.csv"), FitError);
  try {
    (void)read_csv("no/such/file.csv");
    FAIL();
  } catch (const FitError& e) {
    EXPECT_EQ(std::string(e.what()), "no/such/file.csv: error: cannot read the file: No such file or directory");
  }
}

// Fields go into JSON output and fitted files, which are UTF-8: a subject named in Latin-1 made
// `calibrate fit --json` stop with nlohmann's raw type_error 316, exit 2 (docs/RELIABILITY.md, F25).
// The reader now refuses the line, saying which byte and how to fix it; comments may hold anything.
TEST(Csv, AFieldThatIsNotUtf8IsRefusedAtItsLine) {
  try {
    parse_csv("# M\xfcller's lab\nsubject,response\nS1,3\nM\xfcller,4\n", "t.csv");
    FAIL() << "a Latin-1 field was read";
  } catch (const FitError& e) {
    EXPECT_EQ(e.line, 4);
    EXPECT_EQ(std::string(e.what()), "t.csv:4: error: byte 2 of the line (0xFC) is not UTF-8; save the file as UTF-8 "
                                     "(a spreadsheet's \"CSV UTF-8\")");
  }
  EXPECT_EQ(parse_csv("subject,response\nM\xc3\xbcller,4\n", "t.csv").rows.at(0).fields.at(0), "M\xc3\xbcller");
}

// Column order does not matter and extra columns are ignored.
TEST(Csv, MagnitudeEstimationColumnsInAnyOrder) {
  const auto d = parse_magnitude_estimation_csv(
      "response,run,period_mm,force_N,stimulus,subject,note\n"
      "4.5,1,2.5,+0.75,a39p25,S1,\"loud, rough\"\n"
      ",1,2.5,0.75,a39p25,S2,no answer\n",
      "m.csv");
  ASSERT_EQ(d.trials.size(), 2u);
  EXPECT_EQ(d.trials[0].subject, "S1");
  EXPECT_EQ(d.trials[0].stimulus, "a39p25");
  EXPECT_DOUBLE_EQ(d.trials[0].x, 0.75);
  EXPECT_DOUBLE_EQ(d.trials[0].period_m, 2.5e-3);
  EXPECT_DOUBLE_EQ(*d.trials[0].response, 4.5);
  EXPECT_EQ(d.trials[0].line, 2);
  EXPECT_FALSE(d.trials[1].response.has_value());
}
