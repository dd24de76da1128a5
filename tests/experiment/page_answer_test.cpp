// The subject page's answer reader (page_answer.hpp): a body is taken only for the screen it
// names, and only an answer the screen allows is accepted; what is accepted reads back in range.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/experiment/page_answer.hpp"

namespace sandpaper::experiment {
namespace {

using nlohmann::json;

// The refusal for `body` posted to screen number 7, or "" with the answer in `out`.
std::string post(const json& screen, const std::string& body, json& out) {
  json parsed;
  if (auto why = parse_page_answer(body, 7, parsed); !why.empty()) return why;
  if (auto why = page_answer_refusal(screen, parsed); !why.empty()) return why;
  out = parsed;
  return "";
}

TEST(PageAnswer, ABodyIsReadOnlyForTheScreenItNames) {
  const json instructions = {{"kind", "instructions"}};
  json a = json{{"kept", true}};
  EXPECT_EQ(post(instructions, "{\"seq\": 7", a), "the answer is not JSON");
  EXPECT_EQ(post(instructions, "", a), "the answer is not JSON");
  for (const char* other : {"[7]", "7", "\"seq\"", "{}", "{\"seq\": 6}", "{\"seq\": \"7\"}", "{\"seq\": 7.0}",
                            "{\"seq\": 18446744073709551615}", "{\"seq\": -7}"})
    EXPECT_EQ(post(instructions, other, a), "this answer is for another screen; reload the page") << other;
  EXPECT_EQ(a, json({{"kept", true}})) << "a refused body changed the answer";
  EXPECT_EQ(post(instructions, "{\"seq\": 7, \"anything\": [1, 2]}", a), "");
  EXPECT_EQ(a["anything"], json({1, 2}));
}

TEST(PageAnswer, EstimatesArePositiveAndConfidencesWithin0To100) {
  const json estimate = {{"kind", "estimate"}}, confidence = {{"kind", "confidence"}};
  json a;
  for (const char* bad : {"{\"seq\":7}", "{\"seq\":7,\"value\":0}", "{\"seq\":7,\"value\":-3}", "{\"seq\":7,\"value\":\"5\"}",
                          "{\"seq\":7,\"value\":1e400}", "{\"seq\":7,\"value\":null}"})
    EXPECT_NE(post(estimate, bad, a), "") << bad;
  EXPECT_EQ(post(estimate, "{\"seq\":7,\"value\":0.25}", a), "");
  EXPECT_EQ(answer_value(a), 0.25);
  EXPECT_EQ(post(confidence, "{\"seq\":7,\"value\":100.5}", a), "give a number from 0 to 100");
  EXPECT_EQ(post(confidence, "{\"seq\":7,\"value\":0}", a), "");
  EXPECT_EQ(answer_value(a), 0.0);
}

TEST(PageAnswer, AnIntervalIsOneOrTwo) {
  const json interval = {{"kind", "interval"}};
  json a;
  for (const char* bad : {"{\"seq\":7,\"interval\":3}", "{\"seq\":7,\"interval\":true}", "{\"seq\":7,\"interval\":\"1\"}",
                          "{\"seq\":7,\"interval\":1.5}", "{\"seq\":7}"})
    EXPECT_EQ(post(interval, bad, a), "answer 1 or 2") << bad;
  EXPECT_EQ(post(interval, "{\"seq\":7,\"interval\":2}", a), "");
  EXPECT_EQ(answer_interval(a), 2);
}

TEST(PageAnswer, ASortGivesEveryPatchOneOfThePilesAndUsesThemAll) {
  const json sort = {{"kind", "sort"}, {"patches", 4}, {"piles", 2}};
  json a;
  EXPECT_EQ(post(sort, "{\"seq\":7,\"assignment\":[1,2,1]}", a), "give every patch a pile");
  EXPECT_EQ(post(sort, "{\"seq\":7,\"assignment\":{\"0\":1}}", a), "give every patch a pile");
  EXPECT_EQ(post(sort, "{\"seq\":7,\"assignment\":[1,1,1,1]}", a), "use every pile");
  // 2^32 + 1 was pile 1 when piles were read as int (F29); 2^64 - 1 reads as -1 in 64 bits.
  for (const char* pile : {"0", "3", "4294967297", "18446744073709551615", "-1", "1.0", "\"1\""})
    EXPECT_EQ(post(sort, std::string("{\"seq\":7,\"assignment\":[1,2,1,") + pile + "]}", a), "piles are numbered 1 to 2") << pile;
  EXPECT_EQ(post(sort, "{\"seq\":7,\"assignment\":[2,1,1,2]}", a), "");
  EXPECT_EQ(answer_piles(a), (std::vector<int>{1, 0, 0, 1}));
}

}  // namespace
}  // namespace sandpaper::experiment
