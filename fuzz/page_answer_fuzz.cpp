// The subject page's answers (experiments: page_answer.hpp), as POST /api/answer reads them:
// the first four bytes make the screen being answered (its kind; for a sort, patches 1-16 and piles
// 1-patches; its number 0-255), the rest is the request body. Each accepted answer is checked
// against an independent statement of the screen's rule (docs/EXPERIMENTS.md, "The subject's page"),
// as the observer then reads it; each refusal must be one of the page's messages and leave the
// answer as it was. The reader throws nothing: nothing is caught here.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "fuzz_support.hpp"
#include "sandpaper/experiment/page_answer.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace {

using nlohmann::json;
using sandpaper::fuzz::check;

const char* const kKinds[] = {"estimate", "confidence", "interval", "sort", "instructions", "rest"};

bool is_page_message(const std::string& why, std::int64_t piles) {
  for (const char* m : {"the answer is not JSON", "this answer is for another screen; reload the page", "give a positive number",
                        "give a number from 0 to 100", "answer 1 or 2", "give every patch a pile", "use every pile"})
    if (why == m) return true;
  return why == "piles are numbered 1 to " + std::to_string(piles);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  if (size < 4) return 0;
  const std::string kind = kKinds[data[0] % std::size(kKinds)];
  const std::int64_t patches = 1 + data[1] % 16, piles = 1 + data[2] % patches, seq = data[3];
  json screen = {{"kind", kind}};
  if (kind == "sort") screen.update(json{{"patches", patches}, {"piles", piles}});
  const std::string_view body(reinterpret_cast<const char*>(data) + 4, size - 4);

  const json untouched = {{"untouched", true}};
  json answer = untouched;
  std::string why = experiment::parse_page_answer(body, seq, answer);
  if (!why.empty()) {
    check(answer == untouched, "a refused body changed the answer");
  } else {
    const auto s = answer.find("seq");
    check(answer.is_object() && s != answer.end() && s->is_number_integer() && *s == seq,
          "an answer was taken for another screen: " + schema::json_text(answer));
    why = experiment::page_answer_refusal(screen, answer);
  }
  if (!why.empty()) {
    check(is_page_message(why, piles), "a refusal the page does not know: " + why);
    (void)schema::json_text(json{{"error", why}});  // the server's 400 body
    return 0;
  }

  if (kind == "estimate" || kind == "confidence") {
    const double v = experiment::answer_value(answer);
    check(std::isfinite(v) && v >= 0 && (kind == "estimate" ? v > 0 : v <= 100),
          kind + " " + std::to_string(v) + " accepted");
  } else if (kind == "interval") {
    const int i = experiment::answer_interval(answer);
    check((i == 1 || i == 2) && answer["interval"] == i, "interval " + answer["interval"].dump() + " accepted as " + std::to_string(i));
  } else if (kind == "sort") {
    const std::vector<int> p = experiment::answer_piles(answer);
    check(static_cast<std::int64_t>(p.size()) == patches, "a sort with " + std::to_string(p.size()) + " piles for " +
                                                              std::to_string(patches) + " patches accepted");
    std::vector<int> count(static_cast<std::size_t>(piles), 0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      check(p[i] >= 0 && p[i] < piles && answer["assignment"][i] == p[i] + 1,
            "pile " + answer["assignment"][i].dump() + " read as " + std::to_string(p[i]) + " of " + std::to_string(piles));
      ++count[static_cast<std::size_t>(p[i])];
    }
    for (int c : count) check(c > 0, "a sort leaving a pile empty accepted");
  }
  return 0;
}
