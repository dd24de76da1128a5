// Picture -> one height per sample. The rule (docs/TEXTURES.md, "Real images"): one channel is the
// height; two are grey + alpha; three or more give Rec. 709 luminance of R, G, B (alpha and any
// others ignored); `channel NAME` picks one channel instead.
#include "sandpaper/compiler/height_image.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/schema/array_file.hpp"

namespace sandpaper::compiler {
namespace {

std::string mm(double m) {
  std::ostringstream os;
  os.precision(4);
  os << m * 1e3 << " mm";
  return os.str();
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// All channels of the picture, interleaved, as float.
struct RawImage {
  int nx = 0, ny = 0, nc = 0;
  std::vector<float> pixels;
  std::vector<std::string> channel_names;
  std::string format;  // "uint8", "half", ".depth (uint8)"
};

bool fail(HeightImageError& e, std::string code, std::string message, std::string suggestion) {
  e = {std::move(code), std::move(message), std::move(suggestion)};
  return false;
}

bool check_dimensions(const HeightImageRequest& r, long long nx, long long ny, const char* unit, HeightImageError& e) {
  if (nx <= 0 || ny <= 0)
    return fail(e, "E0402",
                "image '" + r.shown_path + "' is empty (" + std::to_string(nx) + " x " + std::to_string(ny) + " " + unit + ")",
                "use an image with at least 3 x 3 pixels");
  if (nx * ny > kMaxImagePixels)
    return fail(e, "E0402",
                "image '" + r.shown_path + "' has " + std::to_string(nx) + " x " + std::to_string(ny) + " = " +
                    std::to_string(nx * ny) + " " + unit + ", more than the limit of 4096 x 4096",
                "scale the image down before using it");
  return true;
}

bool read_depth_file(const HeightImageRequest& r, RawImage& raw, HeightImageError& e) {
  std::ifstream in(r.path, std::ios::binary);
  if (!in)
    return fail(e, "E0401",
                "cannot read array file '" + r.shown_path + "': " +
                    (std::filesystem::exists(r.path) ? "it cannot be opened" : "no such file"),
                "check the path (relative to the material file's folder)");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  schema::ArrayFile a;
  try {
    a = schema::decode_array(bytes, r.shown_path);
  } catch (const schema::ArrayFileError& x) {
    return fail(e, "E0405", x.what(), "the file is truncated or not a Sandpaper array file; write it again with `sandpaper array`");
  }
  if (!check_dimensions(r, a.width, a.height, "items", e)) return false;
  raw.nx = a.width;
  raw.ny = a.height;
  raw.nc = 1;
  raw.channel_names = {"depth"};
  raw.format = ".depth, uint8";
  raw.pixels.resize(a.values.size());
  // 0 is the lowest (Appendix B); scaled like an 8-bit image so that both read alike.
  for (std::size_t i = 0; i < a.values.size(); ++i) raw.pixels[i] = static_cast<float>(a.values[i]) / 255.0f;
  return true;
}

bool read_picture(const HeightImageRequest& r, RawImage& raw, HeightImageError& e) {
  // Heights are the values as stored: no premultiplying by alpha (PNG, TIFF and others would).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(r.path, &config);
  if (!in) {
    std::string why = OIIO::geterror();
    return fail(e, "E0401", "cannot read image '" + r.shown_path + "': " + (why.empty() ? "unreadable" : why),
                "check the path (relative to the material file's folder) and that the file is an image");
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (!check_dimensions(r, spec.width, spec.height, "px", e)) return false;
  if (spec.nchannels < 1)
    return fail(e, "E0402", "image '" + r.shown_path + "' has no channels", "use an image with at least one channel");
  raw.nx = spec.width;
  raw.ny = spec.height;
  raw.nc = spec.nchannels;
  for (int c = 0; c < raw.nc; ++c) {
    std::string name = c < static_cast<int>(spec.channelnames.size()) ? spec.channelnames[static_cast<std::size_t>(c)] : "";
    raw.channel_names.push_back(name.empty() ? "channel" + std::to_string(c) : name);
  }
  raw.format = spec.format.c_str();
  raw.pixels.resize(static_cast<std::size_t>(raw.nx) * raw.ny * raw.nc);
  // Integer pixels arrive normalised to 0..1; float pixels as stored (no assumption of 0..1).
  if (!in->read_image(0, 0, 0, raw.nc, OIIO::TypeDesc::FLOAT, raw.pixels.data())) {
    std::string why = in->geterror();
    return fail(e, "E0401", "cannot read image '" + r.shown_path + "': " + (why.empty() ? "read failed" : why),
                "the file may be truncated or corrupt");
  }
  in->close();
  return true;
}

// The heights from the channels, by the rule at the top of this file; `how` describes it.
bool select_heights(const HeightImageRequest& r, const RawImage& raw, std::vector<float>& out, std::string& how,
                    HeightImageError& e) {
  std::vector<float> weight(static_cast<std::size_t>(raw.nc), 0.0f);
  auto index_of = [&](const std::string& n) {
    auto it = std::find(raw.channel_names.begin(), raw.channel_names.end(), n);
    return it == raw.channel_names.end() ? -1 : static_cast<int>(it - raw.channel_names.begin());
  };
  if (!r.channel.empty()) {
    int c = index_of(r.channel);
    if (c < 0) {
      // A different case is the likeliest slip ("r" for "R"); else an edit-distance guess for names
      // long enough that a guess means something.
      std::string guess;
      for (const auto& n : raw.channel_names)
        if (n.size() == r.channel.size() &&
            std::equal(n.begin(), n.end(), r.channel.begin(), [](char a, char b) { return std::tolower(a) == std::tolower(b); }))
          guess = n;
      if (guess.empty() && r.channel.size() >= 3) guess = closest_match(r.channel, raw.channel_names);
      return fail(e, "E0404",
                  "image '" + r.shown_path + "' has no channel '" + r.channel + "'; its channels are " + join(raw.channel_names),
                  guess.empty() ? "name one of its channels, or leave `channel` out for the luminance rule"
                                : "did you mean `channel " + guess + "`?");
    }
    weight[static_cast<std::size_t>(c)] = 1.0f;
    how = "channel " + r.channel;
  } else if (raw.nc <= 2) {
    weight[0] = 1.0f;  // grey, or grey + alpha
    how = raw.nc == 1 ? "grey level" : "grey level (" + raw.channel_names[1] + " ignored)";
  } else {
    int ri = index_of("R"), gi = index_of("G"), bi = index_of("B");
    if (ri < 0 || gi < 0 || bi < 0) ri = 0, gi = 1, bi = 2;
    weight[static_cast<std::size_t>(ri)] = 0.2126f;
    weight[static_cast<std::size_t>(gi)] = 0.7152f;
    weight[static_cast<std::size_t>(bi)] = 0.0722f;
    how = "Rec. 709 luminance of " + raw.channel_names[static_cast<std::size_t>(ri)] + ", " +
          raw.channel_names[static_cast<std::size_t>(gi)] + ", " + raw.channel_names[static_cast<std::size_t>(bi)];
  }
  std::size_t n = static_cast<std::size_t>(raw.nx) * raw.ny;
  out.assign(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &raw.pixels[i * static_cast<std::size_t>(raw.nc)];
    float v = 0;
    for (int c = 0; c < raw.nc; ++c)
      if (weight[static_cast<std::size_t>(c)] != 0.0f) v += weight[static_cast<std::size_t>(c)] * p[c];
    out[i] = v;
  }
  return true;
}

}  // namespace

std::optional<HeightImage> load_height_image(const HeightImageRequest& r, HeightImageError& e) {
  auto kind = schema::array_kind_of(r.path);
  if (kind == schema::ArrayKind::Shade) {
    fail(e, "E0406",
         "'" + r.shown_path + "' is a Sandpaper .shade file: a shaded picture of a surface (0 = white), not its heights",
         "use the surface's .depth file as the height map");
    return std::nullopt;
  }
  RawImage raw;
  if (!(kind == schema::ArrayKind::Depth ? read_depth_file(r, raw, e) : read_picture(r, raw, e))) return std::nullopt;

  HeightImage img;
  std::string how;
  if (!select_heights(r, raw, img.values, how, e)) return std::nullopt;
  raw.pixels = {};
  for (float v : img.values)
    if (!std::isfinite(v)) {
      fail(e, "E0403", "image '" + r.shown_path + "' holds non-finite values (NaN or infinity)",
           "replace them before using the image as a height map");
      return std::nullopt;
    }
  auto [lo, hi] = std::minmax_element(img.values.begin(), img.values.end());
  img.lo = *lo;
  img.hi = *hi;
  if (!(img.hi > img.lo)) {
    std::ostringstream v;
    v << img.lo;
    fail(e, "E0403",
         "image '" + r.shown_path + "' is all one height (" + v.str() + ", from its " + how + "): it has no slope, so no lateral force",
         raw.nc > 1 && r.channel.empty() ? "use an image with some variation, or pick a channel that varies with `channel NAME`"
                                         : "use an image with some variation in grey level");
    return std::nullopt;
  }
  if (r.invert)  // dark = high, over the same range
    for (float& v : img.values) v = img.lo + img.hi - v;
  img.nx = img.source_nx = raw.nx;
  img.ny = img.source_ny = raw.ny;

  std::ostringstream d;
  d << raw.nx << " x " << raw.ny << (kind == schema::ArrayKind::Depth ? " items" : " px") << ", " << raw.nc << " channel"
    << (raw.nc > 1 ? "s " : " ") << join(raw.channel_names) << " (" << raw.format << "), height = " << how
    << (r.invert ? ", inverted" : "");

  if (r.sampling_m) {
    double s = *r.sampling_m;
    double fx = std::max(1.0, std::round(r.width_m / s)), fy = std::max(1.0, std::round(r.height_m / s));
    if (fx * fy > static_cast<double>(kMaxImagePixels)) {
      std::ostringstream os;
      os << "sampling " << mm(s) << " over " << mm(r.width_m) << " x " << mm(r.height_m) << " makes " << fx << " x " << fy
         << " samples, more than the limit of 4096 x 4096";
      fail(e, "E0402", os.str(),
           "use a sampling of at least " + mm(std::sqrt(r.width_m * r.height_m / static_cast<double>(kMaxImagePixels))));
      return std::nullopt;
    }
    int tx = static_cast<int>(fx), ty = static_cast<int>(fy);
    if (tx < 3 || ty < 3) {
      fail(e, "E0402",
           "sampling " + mm(s) + " over " + mm(r.width_m) + " x " + mm(r.height_m) + " makes " + std::to_string(tx) +
               " x " + std::to_string(ty) + " samples; a height map needs at least 3 x 3",
           "use a sampling of at most " + mm(std::min(r.width_m, r.height_m) / 3));
      return std::nullopt;
    }
    if (tx != raw.nx || ty != raw.ny) {
      OIIO::ImageBuf src(OIIO::ImageSpec(raw.nx, raw.ny, 1, OIIO::TypeDesc::FLOAT), img.values.data());
      // Lanczos-3 to shrink (OpenImageIO's default); to enlarge, Catmull-Rom, an interpolating
      // cubic: it keeps a ramp's slope, where the default Blackman-Harris bump ripples it.
      const char* filter = tx > raw.nx || ty > raw.ny ? "catmull-rom" : "lanczos3";
      OIIO::ImageBuf dst = OIIO::ImageBufAlgo::resize(src, filter, 0.0f, OIIO::ROI(0, tx, 0, ty, 0, 1, 0, 1));
      std::vector<float> resized(static_cast<std::size_t>(tx) * ty);
      if (dst.has_error() || !dst.get_pixels(OIIO::ROI(0, tx, 0, ty, 0, 1, 0, 1), OIIO::TypeDesc::FLOAT, resized.data()))
        throw InternalError("resize of '" + r.shown_path + "' failed: " + dst.geterror());
      img.values = std::move(resized);
      img.nx = tx;
      img.ny = ty;
      d << ", resampled to " << tx << " x " << ty;
    }
  } else if (raw.nx < 3 || raw.ny < 3) {
    fail(e, "E0402",
         "image '" + r.shown_path + "' is " + std::to_string(raw.nx) + " x " + std::to_string(raw.ny) +
             " px; a height map needs at least 3 x 3",
         "use a larger image, or resample it with `sampling`");
    return std::nullopt;
  }
  img.description = d.str();
  return img;
}

}  // namespace sandpaper::compiler
