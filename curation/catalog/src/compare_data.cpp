// One entry's data for the compare page (compare_data.hpp).
#include "sandpaper/catalog/compare_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <nlohmann/json.hpp>

#include "sandpaper/catalog/html.hpp"
#include "sandpaper/compiler/syntax.hpp"

namespace sandpaper::catalog {
namespace {

double rounded(double v, const char* format) {
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return std::strtod(buf, nullptr);
}

}  // namespace

std::string compare_data_file(const std::string& name) { return name + ".compare.js"; }

std::string compare_data_script(const IndexRow& row, const std::string& family_title, const std::string& device,
                                const std::string& terms, const ForceScan& scan, double window_m) {
  using nlohmann::json;
  json sources = json::array();
  for (const auto k : {compiler::SourceKind::Measurement, compiler::SourceKind::Standard, compiler::SourceKind::Publication,
                       compiler::SourceKind::Derived, compiler::SourceKind::ByEar})
    if (row.source_kinds & (1u << static_cast<unsigned>(k))) sources.push_back(compiler::source_kind_word(k));
  // The curve kept within 0.1 % of the plot's width and height, whatever axes the page gives it:
  // the page's axes span at least this scan's length and force.
  double lo = 0, hi = 0;
  for (const double f : scan.along_N) lo = std::min(lo, f), hi = std::max(hi, f);
  const double length = scan.s_m.empty() ? 0 : scan.s_m.back() - scan.s_m.front();
  std::vector<double> x(scan.s_m.size()), y(scan.s_m.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = length > 0 ? scan.s_m[i] / length : 0;
    y[i] = hi > lo ? scan.along_N[i] / (hi - lo) : 0;
  }
  const auto keep = kept_points(x, y, 1e-3);
  json s_mm = json::array(), along = json::array();
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) {
      s_mm.push_back(rounded(scan.s_m[i] * 1e3, "%.4f"));
      along.push_back(rounded(scan.along_N[i], "%.4g"));
    }
  const json data = {{"format", 1},
                     {"name", row.name},
                     {"describes", row.describes},
                     {"family", family_title},
                     {"licence", row.licence},
                     {"root", row.root},
                     {"roughness", row.roughness ? json(*row.roughness) : json(nullptr)},
                     {"max_lateral_force_N", row.max_lateral_force_N},
                     {"period_m", row.period_m},
                     {"kind", row.kind.substr(0, row.kind.find('|'))},
                     {"terms", terms},
                     {"sources", sources},
                     {"device", device},
                     {"thumbnail", row.thumbnail.empty() ? json(nullptr) : json(row.name + "-thumb.png")},
                     {"window_m", window_m},
                     {"scan",
                      {{"description", scan.description}, {"speed_m_s", scan.speed_m_s}, {"s_mm", s_mm}, {"along_N", along}}}};
  return json_statement("(window.sandpaperCompare = window.sandpaperCompare || []).push(JSON.parse('",
                        data.dump(-1, ' ', true), "'));\n");
}

}  // namespace sandpaper::catalog
