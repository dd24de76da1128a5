#include <algorithm>

#include "file_reading.hpp"

namespace sandpaper::calibration::detail {
namespace {

void read_force_jnd(const Toml& f, ForceJndData& out) {
  const toml::table& c = f.doc;
  out.file = f.shown_as;
  out.weber_fraction = *c["weber_fraction"].value<double>();
  out.weber_rationale = *c["rationale"].value<std::string>();
  for (const auto& node : *c["jnd"].as_array()) {
    const toml::table& j = *node.as_table();
    ForceJnd x;
    x.id = *j["id"].value<std::string>();
    x.relative = *j["kind"].value<std::string>() == "relative";
    if (const auto* fr = j["fraction"].as_array()) {
      x.fraction_min = *fr->get(0)->value<double>();
      x.fraction_max = *fr->get(1)->value<double>();
    }
    if (auto v = j["value"].node()) x.absolute_N = quantity_si(*v);
    if (const auto* r = j["reference_force"].as_array()) {
      x.force_min_N = quantity_si(*r->get(0));
      x.force_max_N = quantity_si(*r->get(1));
    }
    x.effector = *j["effector"].value<std::string>();
    x.citation = *j["citation"].value<std::string>();
    x.where = *j["where"].value<std::string>();
    out.jnds.push_back(std::move(x));
  }
}

}  // namespace

void load_knowledge(const std::filesystem::path& dir, const ShownPath& shown, Knowledge& out, Problems& problems) {
  if (auto f = read_validated(dir / "force-jnd.toml", shown(dir / "force-jnd.toml"), "force-jnd", problems))
    read_force_jnd(*f, out.force_jnd);
}

}  // namespace sandpaper::calibration::detail
