// `sandpaper array`: a picture -> Sandpaper's own array files (Minsky 1995, Appendix B): the 8-bit
// height array (.depth) and, optionally, the shaded picture Sandpaper's Normal display drew (.shade).
#include <charconv>
#include <cmath>
#include <iostream>
#include <stdexcept>

#include "cli.hpp"
#include "sandpaper/compiler/array_export.hpp"
#include "sandpaper/schema/array_file.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::cli {
namespace {

struct Length {
  double value = 0;
  std::optional<double> to_si;  // none: no unit written
};

Length parse_length_part(const std::string& text, const std::string& whole) {
  Length l;
  const char* b = text.data();
  const char* e = b + text.size();
  auto [p, ec] = std::from_chars(b, e, l.value);
  if (ec != std::errc() || !std::isfinite(l.value) || l.value <= 0)
    throw std::invalid_argument("'" + whole + "' is not a positive length: write e.g. 80mm or 80x60mm");
  std::string unit(p, e);
  if (unit.empty()) return l;
  auto def = schema::find_unit(unit);
  if (!def || def->dimension != schema::Dimension::Length)
    throw std::invalid_argument("'" + unit + "' in '" + whole + "' is not a length unit: use one of " +
                                schema::units_of(schema::Dimension::Length));
  l.to_si = def->to_si;
  return l;
}

std::string without_spaces(std::string s) {
  std::erase(s, ' ');
  return s;
}

// "0.37mm" -> 0.00037 (m).
double parse_length(const std::string& text) {
  std::string s = without_spaces(text);
  Length l = parse_length_part(s, text);
  if (!l.to_si) throw std::invalid_argument("'" + text + "' has no unit: write e.g. " + text + "mm");
  return l.value * *l.to_si;
}

// "80mm", "80x60mm" (one unit for both), "80mmx60mm" -> width and height, m.
std::pair<double, double> parse_size(const std::string& text) {
  std::string s = without_spaces(text);
  auto x = s.find('x');
  if (x == std::string::npos) {
    double w = parse_length(s);
    return {w, w};
  }
  Length w = parse_length_part(s.substr(0, x), text), h = parse_length_part(s.substr(x + 1), text);
  if (!h.to_si) throw std::invalid_argument("'" + text + "' has no unit: write e.g. 80x60mm");
  if (!w.to_si) w.to_si = h.to_si;
  return {w.value * *w.to_si, h.value * *h.to_si};
}

}  // namespace

int cmd_array(const ArrayOptions& o) {
  if (schema::array_kind_of(o.output) != schema::ArrayKind::Depth) {
    std::cerr << "sandpaper array: the height array's name must end in .depth (Sandpaper's convention, thesis "
                 "Appendix B), not '" << o.output << "'\n";
    return kExitUsage;
  }
  if (!o.shade.empty() && schema::array_kind_of(o.shade) != schema::ArrayKind::Shade) {
    std::cerr << "sandpaper array: the shaded picture's name must end in .shade, not '" << o.shade << "'\n";
    return kExitUsage;
  }
  auto [width, height] = parse_size(o.size);
  compiler::HeightFieldImageRequest req;
  req.path = req.shown_path = o.image;
  req.channel = o.channel;
  req.invert = o.invert;
  req.width_m = width;
  req.height_m = height;
  if (!o.sampling.empty()) req.sampling_m = parse_length(o.sampling);
  std::optional<double> depth;
  if (!o.depth.empty()) depth = parse_length(o.depth);
  compiler::HeightFieldImageError err;
  auto img = compiler::load_height_field_image(req, err);
  if (!img) {
    std::cerr << "sandpaper array: error[" << err.code << "]: " << err.message << "\n = help: " << err.suggestion << "\n";
    return kExitBadInput;
  }
  // Both are computed before either is written, so a failure leaves neither half-made.
  auto heights = compiler::quantize_depth(*img);
  std::optional<schema::ArrayFile> picture;
  if (!o.shade.empty()) picture = compiler::shade_relief(*img, width / img->nx, height / img->ny, depth);
  schema::write_depth_file(o.output, heights);
  if (picture) schema::write_shade_file(o.shade, *picture);
  std::cout << o.image << " -> " << o.output << ": " << img->nx << " x " << img->ny << " items, "
            << width / img->nx * 1e3 << " mm x " << height / img->ny * 1e3 << " mm each (" << img->description << ")";
  if (picture) std::cout << "; shaded picture -> " << o.shade;
  std::cout << "\n";
  return kExitOk;
}

}  // namespace sandpaper::cli
