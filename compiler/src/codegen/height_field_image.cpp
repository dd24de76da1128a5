// Picture -> one height per sample. The rule (docs/TEXTURES.md, "Real images"): one channel is the
// height; two are grey + alpha; three or more give Rec. 709 luminance of R, G, B (alpha and any
// others ignored); `channel NAME` picks one channel instead.
#include "sandpaper/compiler/height_field_image.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <utility>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/image_io.hpp"
#include "sandpaper/schema/array_file.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/no_coverage.hpp"
#include "exr_header.hpp"
#include "png_chunks.hpp"

namespace sandpaper::compiler {
namespace {

// The height channels of a picture, read as 32-bit floats: at most 256 MiB (4096 x 4096 x R, G, B
// is 192 MiB). Checked from the header, before any pixel is allocated.
constexpr std::uint64_t kMaxImageReadBytes = std::uint64_t{256} << 20;

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

// The picture's channels [first, first + read) interleaved as float (only those the height uses
// are read), and the names of all `nc` of them.
struct RawImage {
  int nx = 0, ny = 0, nc = 0;
  int first = 0, read = 0;
  std::vector<float> pixels;
  std::vector<std::string> channel_names;
  std::string format;  // "uint8", "half", ".depth (uint8)"
};

// A decoder's error log can hold one line per scanline: the first says what is wrong.
std::string first_line(const std::string& log) {
  const auto end = log.find('\n');
  if (end == std::string::npos) return log;
  const auto more = static_cast<std::size_t>(std::count(log.begin(), log.end(), '\n'));
  return log.substr(0, end) + " (and " + std::to_string(more) + " more lines like it)";
}

bool fail(HeightFieldImageError& e, schema::Code code, std::string message, std::string suggestion) {
  e = {std::string(code.text()), std::move(message), std::move(suggestion)};
  return false;
}

bool check_dimensions(const HeightFieldImageRequest& r, long long nx, long long ny, const char* unit, HeightFieldImageError& e) {
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

// Under 3 samples a side, without `sampling` to enlarge it: E0402.
bool too_small(const HeightFieldImageRequest& r, const RawImage& raw, HeightFieldImageError& e) {
  if (raw.nx >= 3 && raw.ny >= 3) return false;
  fail(e, "E0402",
       "image '" + r.shown_path + "' is " + std::to_string(raw.nx) + " x " + std::to_string(raw.ny) +
           " px; a height map needs at least 3 x 3",
       "use a larger image, or resample it with `sampling`");
  return true;
}

bool read_depth_file(const HeightFieldImageRequest& r, RawImage& raw, HeightFieldImageError& e) {
  std::string text;
  try {
    text = schema::read_input_file(r.path, schema::limits::kMaxImageFileBytes);
  } catch (const schema::InputFileError& x) {
    return fail(e, "E0401", "cannot read array file '" + r.shown_path + "': " + x.reason,
                "check the path (relative to the material file's folder)");
  }
  std::vector<unsigned char> bytes(text.begin(), text.end());
  text = {};
  schema::ArrayFile a;
  try {
    a = schema::decode_array(bytes, r.shown_path);
  } catch (const schema::ArrayFileError& x) {
    return fail(e, "E0405", x.what(), "the file is truncated or not a Sandpaper array file; write it again with `sandpaper array`");
  }
  if (!check_dimensions(r, a.width, a.height, "items", e)) return false;
  raw.nx = a.width;
  raw.ny = a.height;
  raw.nc = raw.read = 1;
  raw.channel_names = {"depth"};
  raw.format = ".depth, uint8";
  raw.pixels.resize(a.values.size());
  // 0 is the lowest (Appendix B); scaled like an 8-bit image so that both read alike.
  for (std::size_t i = 0; i < a.values.size(); ++i) raw.pixels[i] = static_cast<float>(a.values[i]) / 255.0f;
  return true;
}

// A picture opened through the image table, closed when it goes.
class OpenPicture {
 public:
  OpenPicture() = default;
  explicit OpenPicture(void* p) : p_(p) {}
  OpenPicture(OpenPicture&& o) noexcept : p_(std::exchange(o.p_, nullptr)) {}
  OpenPicture& operator=(OpenPicture&&) = delete;
  ~OpenPicture() {
    if (p_) image_io::api().close(p_);
  }
  explicit operator bool() const { return p_ != nullptr; }
  void* get() const { return p_; }

 private:
  void* p_ = nullptr;
};

// Opens the picture and reads its header: nothing is allocated for pixels yet.
OpenPicture open_picture(const HeightFieldImageRequest& r, RawImage& raw, HeightFieldImageError& e) {
  // A device or FIFO (/dev/zero, a pipe) would make a format probe read forever or block.
  std::error_code ec;
  const auto status = std::filesystem::status(r.path, ec);
  if (status.type() == std::filesystem::file_type::not_found) {
    fail(e, "E0401", "cannot read image '" + r.shown_path + "': no such file",
         "check the path (relative to the material file's folder)");
    return {};
  }
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    fail(e, "E0401", "cannot read image '" + r.shown_path + "': not a regular file (a device, FIFO or directory)",
         "give an image file on disk");
    return {};
  }
  if (!ec && std::filesystem::exists(status) && std::filesystem::file_size(r.path, ec) > schema::limits::kMaxImageFileBytes) {
    fail(e, "E0401",
         "image '" + r.shown_path + "' is larger than the limit of " +
             std::to_string(schema::limits::kMaxImageFileBytes >> 20) + " MiB for a height-map file",
         "scale the image down, or crop it, before using it");
    return {};
  }
  auto overrun = png_chunks_overrun(r.path);
  if (!overrun) overrun = exr_header_overrun(r.path);
  if (overrun) {
    fail(e, "E0401", "cannot read image '" + r.shown_path + "': " + *overrun, "the file may be truncated or corrupt; save it again");
    return {};
  }
  // Heights are the values as stored: no premultiplying by alpha (PNG, TIFF and others would).
  image_io::PictureHeader spec;
  std::string why;
  OpenPicture in(image_io::api().open(r.path, spec, why));
  if (!in) {
    why = first_line(why);
    // Since F21 the extension alone picks the reader (a missing file was reported above).
    fail(e, "E0401", "cannot read image '" + r.shown_path + "': " + (why.empty() ? "unreadable" : why),
         "save the image as PNG, TIFF, OpenEXR, JPEG, BMP, PNM, Radiance HDR or TGA, under that format's extension: "
         "the extension picks the reader");
    return {};
  }
  if (!check_dimensions(r, spec.width, spec.height, "px", e)) return {};
  if (spec.channels < 1) {
    fail(e, "E0402", "image '" + r.shown_path + "' has no channels", "use an image with at least one channel");
    return {};
  }
  if (static_cast<std::uint64_t>(spec.channels) > schema::limits::kMaxImageChannels) {
    fail(e, "E0402",
         "image '" + r.shown_path + "' claims " + std::to_string(spec.channels) + " channels, more than the limit of " +
             std::to_string(schema::limits::kMaxImageChannels),
         "save the channel that holds the heights as a grey image");
    return {};
  }
  // The decoder works a scanline or strip of all channels at a time, whichever it is asked for: the
  // whole image as stored must fit the budget too (a 320-byte header can claim gigabytes).
  const std::uint64_t stored = static_cast<std::uint64_t>(spec.width) * static_cast<std::uint64_t>(spec.height) *
                               static_cast<std::uint64_t>(spec.channels) * std::max<std::uint64_t>(1, spec.format_bytes);
  if (stored > kMaxImageReadBytes) {
    fail(e, "E0402",
         "image '" + r.shown_path + "' claims " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
             " px of " + std::to_string(spec.channels) + " channels (" + std::to_string(stored >> 20) +
             " MiB), over the limit of " + std::to_string(kMaxImageReadBytes >> 20) + " MiB",
         "scale the image down, or save the channel that holds the heights as a grey image");
    return {};
  }
  raw.nx = spec.width;
  raw.ny = spec.height;
  raw.nc = spec.channels;
  for (int c = 0; c < raw.nc; ++c) {
    std::string name = c < static_cast<int>(spec.channel_names.size()) ? spec.channel_names[static_cast<std::size_t>(c)] : "";
    // The file's bytes, not text: they go into diagnostics and the patch program's description,
    // which hold UTF-8 only (docs/RELIABILITY.md, F42).
    raw.channel_names.push_back(name.empty() ? "channel" + std::to_string(c) : schema::replace_invalid_utf8(name));
  }
  raw.format = spec.format;
  return in;
}

// Reads the channels [first, last] of an open picture, within a stated memory budget.
bool read_channels(const HeightFieldImageRequest& r, const OpenPicture& in, int first, int last, RawImage& raw,
                   HeightFieldImageError& e) {
  raw.first = first;
  raw.read = last - first + 1;
  const std::uint64_t bytes = static_cast<std::uint64_t>(raw.nx) * static_cast<std::uint64_t>(raw.ny) *
                              static_cast<std::uint64_t>(raw.read) * sizeof(float);
  if (bytes > kMaxImageReadBytes)
    return fail(e, "E0402",
                "image '" + r.shown_path + "' needs " + std::to_string(bytes >> 20) + " MiB to read its height channels, over the limit of " +
                    std::to_string(kMaxImageReadBytes >> 20) + " MiB",
                "scale the image down, or name the one channel that holds the heights with `channel NAME`");
  raw.pixels.resize(static_cast<std::size_t>(raw.nx) * raw.ny * raw.read);
  // Integer pixels arrive normalised to 0..1; float pixels as stored (no assumption of 0..1).
  // The table also fails a read that OpenImageIO reports as done but logged an error (truncated).
  std::string why;
  if (!image_io::api().read(in.get(), first, last, raw.pixels.data(), why))
    return fail(e, "E0401", "cannot read image '" + r.shown_path + "': " + first_line(why),
                "the file may be truncated or corrupt; save it again");
  return true;
}

// The weight of each channel in the height, by the rule at the top of this file; `how` describes it.
bool choose_weights(const HeightFieldImageRequest& r, const RawImage& raw, std::vector<float>& weight, std::string& how,
                    HeightFieldImageError& e) {
  weight.assign(static_cast<std::size_t>(raw.nc), 0.0f);
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
  return true;
}

// The heights: the weighted sum of the channels read (a per-pixel kernel: no_coverage.hpp).
SANDPAPER_NO_COVERAGE void combine(const RawImage& raw, const std::vector<float>& weight, std::vector<float>& out) {
  const std::size_t n = static_cast<std::size_t>(raw.nx) * raw.ny;
  out.assign(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &raw.pixels[i * static_cast<std::size_t>(raw.read)];
    float v = 0;
    for (int c = 0; c < raw.read; ++c)
      if (const float w = weight[static_cast<std::size_t>(raw.first + c)]; w != 0.0f) v += w * p[c];
    out[i] = v;
  }
}

// Whether every height is finite, and if so their range (a per-pixel kernel: no_coverage.hpp).
SANDPAPER_NO_COVERAGE bool finite_range(const std::vector<float>& v, float& lo, float& hi) {
  lo = v.empty() ? 0.0f : v[0], hi = lo;
  for (const float x : v) {
    if (!std::isfinite(x)) return false;
    lo = std::min(lo, x), hi = std::max(hi, x);
  }
  return true;
}

}  // namespace

// What OpenImageIO's resize (2.4, separable filters, default widths: lanczos3 6 px, catmull-rom
// 4 px) does for each sample, from its source (imagebufalgo_xform.cpp, resize_ and
// get_resize_filter): the filter is fw max(1, ratio) wide along each axis, ratio = samples / pixels,
// and the window it walks is 2 ceil(r / ratio) + 1 pixels along each axis with r = half the x
// width, for y too. So enlarging along x also lengthens the y window, though only the taps inside
// the y filter's support weigh anything; the rest are still stepped over, one at a time, for every
// sample. The y window sits on a worker thread's stack, asserted under 2^20 taps: a 2 x 800,000 px
// TIFF over 3 rows aborted the compiler (F39). Float arithmetic as OpenImageIO's, so the window
// lengths are its own (checked at the 2^20 boundary with oiiotool, both filters).
struct Resample {
  const char* filter;
  long long x_taps, y_taps;
  long long y_live;  // y taps inside the filter's support: only these rows are summed
  long long x_weights;  // x_taps for each of the tx columns, precomputed on the heap (4 bytes each)
  // Pixel visits: samples x (y_live x x_taps + y_taps): each weighted row is summed across the x
  // window, each row outside the filter stepped over. Measured in release (user time), 1.0e8 to
  // 3.6e8 visits/s: fastest with the window inside the picture (4096 x 4096 px to 4095 x 4095 and to
  // 2000 x 2000), slowest where most of it is stepped over or falls outside the picture and is
  // clamped (a 1 x 200 px profile to 902 x 902; 5,000,000 x 1 px to 30 x 30, 1.8e9 in 14 s).
  double visits;
};

Resample resample_plan(int nx, int ny, int tx, int ty) {
  const bool enlarges = tx > nx || ty > ny;
  const float fw = enlarges ? 4.0f : 6.0f;
  const float xr = static_cast<float>(tx) / static_cast<float>(nx), yr = static_cast<float>(ty) / static_cast<float>(ny);
  const float r = fw * std::max(1.0f, xr) / 2.0f, half_h = fw * std::max(1.0f, yr) / 2.0f;
  const auto window = [](float radius, float ratio) { return 2 * static_cast<long long>(std::ceil(radius / ratio)) + 1; };
  Resample p{enlarges ? "catmull-rom" : "lanczos3", window(r, xr), window(r, yr), 0, 0, 0};
  p.y_live = std::min(p.y_taps, window(half_h, yr));
  p.x_weights = p.x_taps * tx;
  p.visits = static_cast<double>(tx) * ty * (static_cast<double>(p.y_live) * static_cast<double>(p.x_taps) + static_cast<double>(p.y_taps));
  return p;
}

// Samples for `sampling` s over the request's width x height (at least 1 a side).
std::pair<double, double> samples_at(const HeightFieldImageRequest& r, double s) {
  return {std::max(1.0, std::round(r.width_m / s)), std::max(1.0, std::round(r.height_m / s))};
}

// Whether a smoothing asked for stays within its budget over fx x fy samples.
bool smoothing_fits(const HeightFieldImageRequest& r, double fx, double fy) {
  return !r.smoothing_m || smoothing_ops(fx, fy, r.width_m / fx, r.height_m / fy, *r.smoothing_m) <= kMaxImageSmoothingOps;
}

// Whether a sampling passes every check below: 3 x 3 to 4096 x 4096 samples, and a resize (when the
// sample grid differs from the pixels) within both resize limits; and the smoothing's budget after.
bool sampling_fits(const HeightFieldImageRequest& r, const RawImage& raw, double s) {
  const auto [fx, fy] = samples_at(r, s);
  if (fx < 3 || fy < 3 || fx * fy > static_cast<double>(kMaxImagePixels)) return false;
  return resample_within_limits(raw.nx, raw.ny, static_cast<int>(fx), static_cast<int>(fy)) && smoothing_fits(r, fx, fy);
}

// E0402 for a resize past the resize limits (resample_within_limits), naming the sampling nearest the
// one asked that fits (1 % steps, finer and coarser, up to a factor of about 20,000 each way) and,
// when the picture is at least 3 x 3 and its smoothing fits over its pixels, the picture's own.
bool refuse_resample(const HeightFieldImageRequest& r, const RawImage& raw, int tx, int ty, const Resample& p, HeightFieldImageError& e) {
  const double s = *r.sampling_m;
  std::ostringstream m;
  m << "sampling " << mm(s) << " over " << mm(r.width_m) << " x " << mm(r.height_m) << " resamples the image's " << raw.nx
    << " x " << raw.ny << " px to " << tx << " x " << ty << " samples: ";
  if (p.y_taps > kMaxResampleTaps)
    m << "OpenImageIO's resize would walk a window of " << p.y_taps << " pixels along y for each sample, more than the limit of "
      << kMaxResampleTaps;
  else if (p.x_weights > kMaxResampleXWeights)
    m << "OpenImageIO's resize would hold " << p.x_taps << " weights for each of the " << tx << " columns, " << p.x_weights
      << " in all, more than the limit of " << kMaxResampleXWeights;
  else
    m << "OpenImageIO's resize would walk a window of " << p.x_taps << " x " << p.y_taps << " pixels for each sample ("
      << p.y_live << " of its rows weighted), about " << p.visits << " pixel visits, more than the limit of "
      << kMaxImageResampleVisits;
  std::string fix;
  for (int k = 1; k <= 1000 && fix.empty(); ++k) {
    for (const double c : {s / std::pow(1.01, k), s * std::pow(1.01, k)})
      if (fix.empty() && sampling_fits(r, raw, c)) fix = "use `sampling " + mm(c) + "`";
  }
  if (raw.nx >= 3 && raw.ny >= 3 && smoothing_fits(r, raw.nx, raw.ny))
    fix += (fix.empty() ? "leave out" : ", or leave out") + std::string(" `sampling` to use the image's ") +
           std::to_string(raw.nx) + " x " + std::to_string(raw.ny) + " px as they are";
  if (fix.empty()) fix = "use an image whose pixels are closer in number to the samples wanted along each side";
  return fail(e, "E0402", m.str(), fix);
}

double smoothing_ops(double nx, double ny, double dx, double dy, double sigma_m) {
  const auto taps = [](double sigma_px) { return sigma_px < 0.3 ? 0.0 : 2 * std::ceil(3 * sigma_px) + 1; };
  return nx * ny * (taps(sigma_m / dx) + taps(sigma_m / dy));
}

bool resample_within_limits(int source_nx, int source_ny, int tx, int ty) {
  if (tx == source_nx && ty == source_ny) return true;
  const auto p = resample_plan(source_nx, source_ny, tx, ty);
  return p.y_taps <= kMaxResampleTaps && p.x_weights <= kMaxResampleXWeights && p.visits <= kMaxImageResampleVisits;
}

std::optional<HeightFieldImage> load_height_field_image(const HeightFieldImageRequest& r, HeightFieldImageError& e) {
  auto kind = schema::array_kind_of(r.path);
  if (kind == schema::ArrayKind::Shade) {
    fail(e, "E0406",
         "'" + r.shown_path + "' is a Sandpaper .shade file: a shaded picture of a surface (0 = white), not its heights",
         "use the surface's .depth file as the height map");
    return std::nullopt;
  }
  RawImage raw;
  HeightFieldImage img;
  std::string how;
  std::vector<float> weight;
  if (kind == schema::ArrayKind::Depth) {
    if (!read_depth_file(r, raw, e) || !choose_weights(r, raw, weight, how, e)) return std::nullopt;
  } else {
    auto in = open_picture(r, raw, e);
    if (!in) return std::nullopt;
    // Too small is known from the header: not decoded first (a 528-byte file can claim 1 x 16,776,449 px).
    if (!r.sampling_m && too_small(r, raw, e)) return std::nullopt;
    if (!choose_weights(r, raw, weight, how, e)) return std::nullopt;
    // Only the channels the height uses are read: a 40-channel header costs nothing unread.
    int first = raw.nc, last = -1;
    for (int c = 0; c < raw.nc; ++c)
      if (weight[static_cast<std::size_t>(c)] != 0.0f) first = std::min(first, c), last = std::max(last, c);
    if (last < 0 || !read_channels(r, in, first, last, raw, e)) return std::nullopt;
  }
  combine(raw, weight, img.values);
  raw.pixels = {};
  float lo = 0, hi = 0;
  if (!finite_range(img.values, lo, hi)) {
    fail(e, "E0403", "image '" + r.shown_path + "' holds non-finite values (NaN or infinity)",
         "replace them before using the image as a height map");
    return std::nullopt;
  }
  img.lo = lo;
  img.hi = hi;
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
      // Lanczos-3 to shrink (OpenImageIO's default); to enlarge, Catmull-Rom, an interpolating
      // cubic: it keeps a ramp's slope, where the default Blackman-Harris bump ripples it.
      const auto plan = resample_plan(raw.nx, raw.ny, tx, ty);
      if (!resample_within_limits(raw.nx, raw.ny, tx, ty)) {
        refuse_resample(r, raw, tx, ty, plan, e);
        return std::nullopt;
      }
      std::vector<float> resized(static_cast<std::size_t>(tx) * ty);
      std::string why;
      if (!image_io::api().resize(img.values.data(), raw.nx, raw.ny, resized.data(), tx, ty, plan.filter, why))
        throw InternalError("resize of '" + r.shown_path + "' failed: " + why);
      img.values = std::move(resized);
      img.nx = tx;
      img.ny = ty;
      d << ", resampled to " << tx << " x " << ty;
    }
  } else if (too_small(r, raw, e)) {
    return std::nullopt;
  }
  img.description = d.str();
  return img;
}

std::optional<std::pair<int, int>> height_field_image_size(const std::string& path) {
  HeightFieldImageRequest r;
  r.path = r.shown_path = path;
  HeightFieldImageError e;
  RawImage raw;
  const auto kind = schema::array_kind_of(path);
  if (kind == schema::ArrayKind::Shade) return std::nullopt;
  if (kind == schema::ArrayKind::Depth) {
    if (!read_depth_file(r, raw, e)) return std::nullopt;
  } else if (!open_picture(r, raw, e)) {
    return std::nullopt;
  }
  return std::pair{raw.nx, raw.ny};
}

}  // namespace sandpaper::compiler
