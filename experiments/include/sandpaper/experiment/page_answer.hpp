#pragma once
// The subject page's answers (docs/EXPERIMENTS.md, "The subject's page"): the body of POST
// /api/answer, JSON, read against the screen it answers. Outside input: whatever reaches the
// experiment's port past the Host/Origin guard, not only the page.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace sandpaper::experiment {

// Parses `body` (the server takes at most 64 KiB) as an answer to the screen numbered `seq`: a JSON
// object whose "seq" is that number. Returns "" and sets `answer`; else the refusal for the page
// (HTTP 400) and `answer` is unchanged. Never throws.
std::string parse_page_answer(std::string_view body, std::int64_t seq, nlohmann::json& answer);

// What makes a parsed answer unacceptable for `screen` (one the experiment made: "kind", and for
// "sort" "patches" and "piles"), in words for the subject; "" when it is acceptable. Never throws.
//   estimate: "value" > 0; confidence: "value" 0 to 100 (finite numbers);
//   interval: "interval" 1 or 2; sort: "assignment", a pile 1..piles per patch, every pile used;
//   any other screen (instructions, rest): anything continues.
std::string page_answer_refusal(const nlohmann::json& screen, const nlohmann::json& answer);

// The content of an answer `page_answer_refusal` accepted for a screen of that kind.
double answer_value(const nlohmann::json& answer);            // estimate, confidence
int answer_interval(const nlohmann::json& answer);            // 1 or 2
std::vector<int> answer_piles(const nlohmann::json& answer);  // per patch, piles counted from 0

}  // namespace sandpaper::experiment
