#include "gltf_support.hpp"
#include "sandpaper/compiler/gltf_document.hpp"
#include "../codegen/png_chunks.hpp"

#include "sandpaper/compiler/image_io.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include <zlib.h>

namespace sandpaper::compiler::gltf {
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

}  // namespace

std::string base64_encode(const std::vector<unsigned char>& bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t{bytes[i]} << 16) | (std::uint32_t{bytes[i + 1]} << 8) | bytes[i + 2];
    for (int s = 18; s >= 0; s -= 6) out.push_back(kAlphabet[(v >> s) & 63]);
  }
  if (i < bytes.size()) {
    std::uint32_t v = std::uint32_t{bytes[i]} << 16;
    if (i + 1 < bytes.size()) v |= std::uint32_t{bytes[i + 1]} << 8;
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

std::optional<std::string> percent_decode(std::string_view uri) {
  auto hex = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1; };
  std::string out;
  out.reserve(uri.size());
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      out += uri[i];
      continue;
    }
    if (i + 2 >= uri.size() || hex(uri[i + 1]) < 0 || hex(uri[i + 2]) < 0) return std::nullopt;
    out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
    i += 2;
  }
  return out;
}

std::optional<std::vector<unsigned char>> base64_decode(std::string_view text) {
  if (text.size() % 4 != 0) return std::nullopt;
  std::array<int, 256> value{};
  value.fill(-1);
  for (int c = 0; c < 64; ++c) value[static_cast<unsigned char>(kAlphabet[c])] = c;
  std::vector<unsigned char> out;
  out.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    int pad = 0;
    std::uint32_t v = 0;
    for (std::size_t j = 0; j < 4; ++j) {
      const unsigned char c = static_cast<unsigned char>(text[i + j]);
      if (c == '=' && last && j >= 2) {
        ++pad;
        v <<= 6;
        continue;
      }
      if (pad > 0 || value[c] < 0) return std::nullopt;  // '=' only at the very end
      v = (v << 6) | static_cast<std::uint32_t>(value[c]);
    }
    out.push_back(static_cast<unsigned char>(v >> 16));
    if (pad < 2) out.push_back(static_cast<unsigned char>(v >> 8));
    if (pad < 1) out.push_back(static_cast<unsigned char>(v));
  }
  return out;
}

std::vector<unsigned char> encode_png16(int nx, int ny, const std::vector<std::uint16_t>& texels) {
  std::vector<unsigned char> bytes;
  std::string why;
  if (!image_io::api().encode_png16(nx, ny, texels.data(), bytes, why)) throw std::runtime_error(why);
  return bytes;
}

namespace {

// A PNG inflated and unfiltered: height rows of width * bytes_per_pixel bytes, samples big-endian.
struct PngRows {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0;
  std::size_t bytes_per_pixel = 0;
  std::vector<unsigned char> rows;
};

// The IHDR fields a decoder chooses by: bit depth, colour type, whether the compression and filter
// methods are PNG's only ones (0), interlace method. Returns the bytes per pixel it reads, or 0 and
// `why` for a kind it does not read.
using HeaderCheck = std::size_t (*)(int depth, int colour, bool standard, int interlace, std::string& why);

// Decoded here rather than by libpng: libpng reports a corrupt stream by longjmp, which leaks
// inside OpenImageIO's reader, and the readers need only a few kinds of PNG. Every chunk's length
// and CRC are checked, and the image data inflates to exactly the bytes its header promises, into a
// buffer sized from the header after the limit.
std::optional<PngRows> inflate_png(const std::vector<unsigned char>& bytes, long long max_pixels, HeaderCheck check, std::string& why) {
  auto fail = [&](std::string w) {
    why = std::move(w);
    return std::nullopt;
  };
  if (bytes.size() < kPngSignature.size() || !std::equal(kPngSignature.begin(), kPngSignature.end(), bytes.begin()))
    return fail("not a PNG (its first bytes are not the PNG signature)");
  auto be32 = [&](std::size_t at) { return png_be32(bytes.data() + at); };
  std::size_t at = kPngSignature.size();
  std::uint32_t width = 0, height = 0;
  std::size_t bpp = 0;
  int depth = 0;
  std::vector<unsigned char> raw;  // the filtered rows, inflated
  z_stream z{};
  bool inflating = false, ended = false, seen_header = false;
  struct End {
    z_stream& z;
    bool& on;
    ~End() {
      if (on) inflateEnd(&z);
    }
  } end{z, inflating};
  while (!ended) {
    if (bytes.size() - at < 12) return fail("the PNG is cut short (a chunk runs past its end)");
    const std::uint32_t length = be32(at);
    if (length > bytes.size() - at - 12) return fail("the PNG is cut short (a chunk runs past its end)");
    const unsigned char* type = bytes.data() + at + 4;
    const unsigned char* data = type + 4;
    if (crc32(crc32(0, nullptr, 0), type, length + 4) != be32(at + 8 + length))
      return fail("the PNG is corrupt (a chunk's CRC does not match)");
    const std::string name(reinterpret_cast<const char*>(type), 4);
    if (!seen_header && name != "IHDR") return fail("the PNG does not start with its header chunk");
    if (name == "IHDR") {
      if (seen_header || length != 13) return fail("the PNG's header chunk is malformed");
      seen_header = true;
      width = be32(at + 8);
      height = be32(at + 12);
      if (width == 0 || height == 0) return fail("the PNG has no pixels");
      if (static_cast<std::uint64_t>(width) * height > static_cast<std::uint64_t>(max_pixels))
        return fail("the PNG claims " + std::to_string(width) + " x " + std::to_string(height) +
                    " px, over the limit of " + std::to_string(max_pixels) + " px");
      std::string kind;
      bpp = check(data[8], data[9], data[10] == 0 && data[11] == 0, data[12], kind);
      if (bpp == 0) return fail(kind);
      depth = data[8];
      raw.resize(static_cast<std::size_t>(height) * (1 + bpp * static_cast<std::size_t>(width)));
      if (inflateInit(&z) != Z_OK) return fail("zlib cannot start");
      inflating = true;
      z.next_out = raw.data();
      z.avail_out = static_cast<uInt>(raw.size());
    } else if (name == "IDAT") {
      if (!inflating) return fail("the PNG's image data comes after its end");
      z.next_in = const_cast<unsigned char*>(data);
      z.avail_in = length;
      while (z.avail_in > 0) {
        const int rc = inflate(&z, Z_NO_FLUSH);
        if (rc == Z_STREAM_END) break;
        if (rc != Z_OK) return fail("the PNG's image data is corrupt (zlib: " + std::string(z.msg ? z.msg : "error") + ")");
        if (z.avail_out == 0 && z.avail_in > 0) return fail("the PNG's image data is longer than its header says");
      }
    } else if (name == "IEND") {
      ended = true;
    } else if (!(type[0] & 0x20)) {
      return fail("the PNG has a critical chunk Sandpaper does not read (" + name + ")");
    }
    at += 12 + length;
  }
  if (!inflating || z.avail_out != 0) return fail("the PNG's image data is shorter than its header says");
  // Undo the row filters (PNG spec 9.2), in place: each row's filter byte is dropped.
  const std::size_t stride = bpp * static_cast<std::size_t>(width);
  PngRows out;
  out.width = width;
  out.height = height;
  out.bit_depth = depth;
  out.bytes_per_pixel = bpp;
  out.rows.resize(static_cast<std::size_t>(height) * stride);
  std::vector<unsigned char> prior(stride, 0);
  for (std::size_t y = 0; y < height; ++y) {
    const unsigned char* in = raw.data() + y * (stride + 1);
    unsigned char* row = out.rows.data() + y * stride;
    const unsigned filter = in[0];
    for (std::size_t i = 0; i < stride; ++i) {
      const int a = i >= bpp ? row[i - bpp] : 0, b = prior[i], c = i >= bpp ? prior[i - bpp] : 0;
      int predicted;
      switch (filter) {
        case 0: predicted = 0; break;
        case 1: predicted = a; break;
        case 2: predicted = b; break;
        case 3: predicted = (a + b) / 2; break;
        case 4: {
          const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
          predicted = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
          break;
        }
        default: return fail("the PNG's row " + std::to_string(y) + " has an unknown filter (" + std::to_string(filter) + ")");
      }
      row[i] = static_cast<unsigned char>(in[1 + i] + predicted);
    }
    std::copy(row, row + stride, prior.begin());
  }
  return out;
}

// Channels per pixel of a colour type (PNG spec 11.2.2): grey, RGB, grey-alpha, RGBA; 0 otherwise.
int channels_of(int colour) { return colour == 0 ? 1 : colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 0; }

}  // namespace

std::optional<Png16> decode_png16(const std::vector<unsigned char>& bytes, long long max_pixels, std::string& why) {
  auto rows = inflate_png(bytes, max_pixels, [](int depth, int colour, bool standard, int interlace, std::string& kind) -> std::size_t {
    if (depth == 16 && colour == 0 && standard && interlace == 0) return 2;
    kind = "the PNG is not 16-bit greyscale without interlacing (bit depth " + std::to_string(depth) +
           ", colour type " + std::to_string(colour) + "), the form Sandpaper writes haptic textures in";
    return 0;
  }, why);
  if (!rows) return std::nullopt;
  Png16 png;
  png.nx = static_cast<int>(rows->width);
  png.ny = static_cast<int>(rows->height);
  png.texels.resize(rows->rows.size() / 2);
  for (std::size_t i = 0; i < png.texels.size(); ++i)
    png.texels[i] = static_cast<std::uint16_t>((rows->rows[2 * i] << 8) | rows->rows[2 * i + 1]);
  return png;
}

}  // namespace sandpaper::compiler::gltf

namespace sandpaper::compiler {

std::optional<GltfValueImage> decode_gltf_value_png(const std::vector<unsigned char>& bytes, long long max_pixels, std::string& why) {
  using namespace gltf;
  auto rows = inflate_png(bytes, max_pixels, [](int depth, int colour, bool standard, int interlace, std::string& kind) -> std::size_t {
    const int channels = channels_of(colour);
    if ((depth == 8 || depth == 16) && channels > 0 && standard && interlace == 0)
      return static_cast<std::size_t>(channels * depth / 8);
    kind = "the PNG is of bit depth " + std::to_string(depth) + ", colour type " + std::to_string(colour) +
           (interlace != 0 ? ", interlaced" : "") +
           "; a texture of values is read from an 8- or 16-bit greyscale, grey-alpha, RGB or RGBA PNG without interlacing";
    return 0;
  }, why);
  if (!rows) return std::nullopt;
  // The first channel of each pixel: grey, or red.
  GltfValueImage out;
  out.nx = static_cast<int>(rows->width);
  out.ny = static_cast<int>(rows->height);
  out.bit_depth = rows->bit_depth;
  const std::size_t n = static_cast<std::size_t>(rows->width) * rows->height, bpp = rows->bytes_per_pixel;
  out.values.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char* px = rows->rows.data() + i * bpp;
    out.values[i] = rows->bit_depth == 16 ? static_cast<float>(((px[0] << 8) | px[1]) / 65535.0) : static_cast<float>(px[0] / 255.0);
  }
  return out;
}

}  // namespace sandpaper::compiler

namespace sandpaper::compiler::gltf {

std::vector<float> grating_forces(const std::vector<double>& h, double period_m, double k_N) {
  const std::size_t n = h.size();
  const double du = period_m / static_cast<double>(n);
  std::vector<float> f(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double before = h[(i + n - 1) % n];
    f[i] = static_cast<float>(-k_N * (h[i] - before) / du);
  }
  return f;
}

void height_field_forces(const std::vector<double>& h, int nx, int ny, double dx_m, double dy_m, bool repeat,
                         double k_N, std::vector<float>& fx, std::vector<float>& fy) {
  const std::size_t size = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  fx.assign(size, 0.0f);
  fy.assign(size, 0.0f);
  auto H = [&](int x, int y) { return h[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x)]; };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      int xl, xr, yd, yu;
      if (repeat) {
        xl = (x - 1 + nx) % nx, xr = (x + 1) % nx, yd = (y - 1 + ny) % ny, yu = (y + 1) % ny;
      } else {
        xl = std::max(x - 1, 0), xr = std::min(x + 1, nx - 1), yd = std::max(y - 1, 0), yu = std::min(y + 1, ny - 1);
      }
      const int span_x = repeat ? 2 : xr - xl, span_y = repeat ? 2 : yu - yd;
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x);
      // A single row or column has no slope across it.
      if (span_x > 0) fx[i] = static_cast<float>(-k_N * (H(xr, y) - H(xl, y)) / (span_x * dx_m));
      if (span_y > 0) fy[i] = static_cast<float>(-k_N * (H(x, yu) - H(x, yd)) / (span_y * dy_m));
    }
}

}  // namespace sandpaper::compiler::gltf
