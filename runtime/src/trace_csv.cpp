#include "sandpaper/runtime/trace_csv.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sandpaper::runtime {
namespace {

constexpr const char* kHeader = "t_s,x_m,y_m,force_x_N,force_y_N";

}  // namespace

std::string format_trace_csv(const std::vector<TickRecord>& records) {
  std::ostringstream csv;
  csv.precision(17);  // max_digits10 of double: the text reads back to the same value
  csv << kHeader << "\n";
  for (const auto& r : records)
    csv << r.t_s << "," << r.position_m.x << "," << r.position_m.y << "," << r.force_N.x << "," << r.force_N.y << "\n";
  return csv.str();
}

std::vector<TickRecord> parse_trace_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::size_t line_no = 1;
  const bool got = static_cast<bool>(std::getline(in, line));
  if (got && !line.empty() && line.back() == '\r') line.pop_back();
  if (!got || line != kHeader)
    throw std::invalid_argument(std::string("trace line 1: expected the header '") + kHeader + "'");
  std::vector<TickRecord> out;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    double v[5];
    const char* p = line.data();
    const char* end = line.data() + line.size();
    for (int i = 0; i < 5; ++i) {
      auto [next, ec] = std::from_chars(p, end, v[i]);
      if (ec != std::errc() || !std::isfinite(v[i]) || (i < 4 && (next == end || *next != ',')) || (i == 4 && next != end))
        throw std::invalid_argument("trace line " + std::to_string(line_no) +
                                    ": expected five finite numbers separated by commas (t_s,x_m,y_m,force_x_N,force_y_N)");
      p = next + 1;
    }
    out.push_back(TickRecord{v[0], {v[1], v[2]}, {v[3], v[4]}});
  }
  return out;
}

}  // namespace sandpaper::runtime
