#include "sandpaper/experiment/page_answer.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace sandpaper::experiment {

using nlohmann::json;

std::string parse_page_answer(std::string_view body, std::int64_t seq, json& answer) {
  // allow_exceptions = false: a body that is not JSON is `discarded`, not an exception.
  json parsed = json::parse(body, nullptr, false);
  if (parsed.is_discarded()) return "the answer is not JSON";
  const auto s = parsed.is_object() ? parsed.find("seq") : parsed.end();
  // An unsigned past 2^63 would read back as a negative number; no screen has one.
  const bool same = s != parsed.end() && s->is_number_integer() &&
                    !(s->is_number_unsigned() && s->get<std::uint64_t>() > std::numeric_limits<std::int64_t>::max()) &&
                    s->get<std::int64_t>() == seq;
  if (!same) return "this answer is for another screen; reload the page";
  answer = std::move(parsed);
  return "";
}

std::string page_answer_refusal(const json& screen, const json& a) {
  const std::string kind = screen.value("kind", "");
  auto number = [&](const char* key) {
    return a.is_object() && a.contains(key) && a[key].is_number() && std::isfinite(a[key].get<double>());
  };
  if (kind == "estimate") return number("value") && a["value"].get<double>() > 0 ? "" : "give a positive number";
  if (kind == "confidence")
    return number("value") && a["value"].get<double>() >= 0 && a["value"].get<double>() <= 100 ? "" : "give a number from 0 to 100";
  if (kind == "interval")
    return a.is_object() && a.contains("interval") && (a["interval"] == 1 || a["interval"] == 2) ? "" : "answer 1 or 2";
  if (kind == "sort") {
    const std::int64_t n = screen.value("patches", std::int64_t{0}), k = screen.value("piles", std::int64_t{0});
    if (!a.is_object() || !a.contains("assignment") || !a["assignment"].is_array() ||
        static_cast<std::int64_t>(a["assignment"].size()) != n)
      return "give every patch a pile";
    std::vector<bool> used(static_cast<std::size_t>(std::max<std::int64_t>(k, 0)), false);
    for (const auto& v : a["assignment"]) {
      // Read as 64 bits: as an int, 4294967297 was pile 1 (F29). An unsigned past 2^63 reads
      // negative and is refused.
      if (!v.is_number_integer() || v.get<std::int64_t>() < 1 || v.get<std::int64_t>() > k)
        return "piles are numbered 1 to " + std::to_string(k);
      used[static_cast<std::size_t>(v.get<std::int64_t>() - 1)] = true;
    }
    for (bool u : used)
      if (!u) return "use every pile";
    return "";
  }
  return "";
}

double answer_value(const json& answer) { return answer.at("value").get<double>(); }

int answer_interval(const json& answer) { return answer.at("interval").get<int>(); }

std::vector<int> answer_piles(const json& answer) {
  std::vector<int> out;
  for (const auto& v : answer.at("assignment")) out.push_back(static_cast<int>(v.get<std::int64_t>() - 1));
  return out;
}

}  // namespace sandpaper::experiment
