#include <gtest/gtest.h>

#include <sstream>

#include "sandpaper/curation/progress.hpp"

namespace sandpaper::curation {
namespace {

TEST(Progress, OffATerminalALineEveryTenEntriesAndTheSummary) {
  std::ostringstream out;
  Progress p("checking", 25, false, out, false);
  for (int i = 0; i < 25; ++i) p.step("e" + std::to_string(i));
  p.finish("checked 25 entries on 3 devices: 0 errors, 0 warnings");
  EXPECT_EQ(out.str(), "checking 10/25\nchecking 20/25\nchecking 25/25\nchecked 25 entries on 3 devices: 0 errors, 0 warnings\n");
}

TEST(Progress, OnATerminalOneCounterLineRewrittenWithCarriageReturns) {
  std::ostringstream out;
  Progress p("indexing", 3, false, out, true);
  p.step("a-long-name");
  p.step("b");
  EXPECT_EQ(out.str().find('\n'), std::string::npos);
  EXPECT_NE(out.str().find("\rindexing 2/3 b"), std::string::npos) << out.str();
  p.finish("done");
  EXPECT_EQ(out.str().back(), '\n');
}

TEST(Progress, QuietPrintsNothing) {
  std::ostringstream out;
  Progress p("checking", 20, true, out, false);
  for (int i = 0; i < 20; ++i) p.step("x");
  p.finish("summary");
  EXPECT_EQ(out.str(), "");
  EXPECT_EQ(p.done(), 20u);
}

}  // namespace
}  // namespace sandpaper::curation
