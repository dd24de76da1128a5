// The picture table (sandpaper/compiler/image_io.hpp) on OpenImageIO. Built twice: as the module
// libsandpaper_image_io.so that the command-line programs load on first use (SANDPAPER_IMAGE_IO_MODULE
// defined: exports sandpaper_image_io_table), and as the static Sandpaper::image_io that applications
// link (defines api() itself).
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstring>
#include <memory>
#include <optional>
#include <string_view>
#include <utility>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "sandpaper/compiler/image_io.hpp"

#include "decoder_buffer.hpp"

namespace sandpaper::compiler::image_io {
namespace {

std::string first_line(std::string s) {
  const auto nl = s.find('\n');
  if (nl != std::string::npos) s.resize(nl);
  return s;
}

// The formats a height map may be in, by file extension (lower case), and OpenImageIO's reader for
// each. Only that reader opens the file: OpenImageIO would otherwise try every reader it has on a
// file its extension's reader refuses (DICOM, FITS, RLA, raw camera files, video through ffmpeg...),
// and its RLA reader aborts the process on a 1 KB file (docs/RELIABILITY.md, F21).
constexpr std::pair<std::string_view, std::string_view> kReaders[] = {
    {"png", "png"},   {"tif", "tiff"}, {"tiff", "tiff"}, {"exr", "openexr"}, {"jpg", "jpeg"},  {"jpeg", "jpeg"},
    {"bmp", "bmp"},   {"pgm", "pnm"},  {"ppm", "pnm"},   {"pnm", "pnm"},     {"pbm", "pnm"},   {"pfm", "pnm"},
    {"hdr", "hdr"},   {"tga", "targa"}};

std::string_view reader_for(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const auto& [e, reader] : kReaders)
    if (ext == e) return reader;
  return {};
}

void* open_picture(const std::string& path, PictureHeader& header, std::string& why) {
  // OpenEXR's C++ reader allocates each header attribute at the size the file claims before reading
  // it: a 620-byte file claiming a 1.9 GB string took 1.9 GB (docs/RELIABILITY.md, F18). OpenEXR
  // Core, which OpenImageIO 2.4 also reads through, checks claimed sizes against the file.
  static const bool exr_core = OIIO::attribute("openexr:core", 1);
  (void)exr_core;
  const auto reader = reader_for(path);
  if (reader.empty()) {
    why = "not a height-map image format by its extension (PNG, TIFF, OpenEXR, JPEG, BMP, PNM, Radiance HDR or TGA: "
          ".png .tif .tiff .exr .jpg .jpeg .bmp .pgm .ppm .pnm .pbm .pfm .hdr .tga)";
    return nullptr;
  }
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::create(reader, false, &config);
  OIIO::ImageSpec opened;
  if (!in || !in->open(path, opened, config)) {
    why = first_line(in ? in->geterror() : OIIO::geterror());
    if (why.empty()) why = "not a " + std::string(reader) + " file";
    return nullptr;
  }
  const OIIO::ImageSpec& spec = in->spec();
  header.width = spec.width;
  header.height = spec.height;
  header.channels = spec.nchannels;
  header.channel_names.assign(spec.channelnames.begin(), spec.channelnames.end());
  header.format = spec.format.c_str();
  header.format_bytes = spec.format.size();
  return in.release();
}

// Rows of a scanline picture read at a time: about this many bytes as stored, in whole TIFF strips.
constexpr std::size_t kStripBytes = std::size_t{1} << 20;

// Channels [first, last] of a scanline picture as floats, read in strips in the file's own format
// and converted here. Asked for floats directly, OpenImageIO 2.4 converts through a buffer of about
// 64 MB whatever the picture's size (ImageInput::read_scanlines sizes it for 64 MB of rows); under
// the fuzzing build's ASan, mapping and poisoning that buffer for every picture was most of the
// image target's time (docs/RELIABILITY.md, "Executions per second"). The conversion is
// OpenImageIO's own, so the values are the same: integers normalised to 0..1, floats as stored.
bool read_strips(OIIO::ImageInput& in, int first, int last, float* pixels) {
  const OIIO::ImageSpec spec = in.spec();
  const std::size_t row_bytes = spec.scanline_bytes(true);
  const std::size_t pixel_bytes = spec.pixel_bytes(true);
  if (row_bytes == 0 || spec.width < 1 || spec.height < 1) return false;
  const int rows_per_strip = std::max(1, spec.get_int_attribute("tiff:RowsPerStrip", 64));
  const int fit = static_cast<int>(std::clamp<std::size_t>(kStripBytes / row_bytes, 1, static_cast<std::size_t>(spec.height)));
  // OpenImageIO 2.4 reads whole deflate TIFF strips itself and then inverts a MinIsWhite picture's
  // values over the strip times its channel count, past the rows it was asked for and past the
  // buffer (docs/RELIABILITY.md, F41). Asked for one row, it takes its per-row path, which inverts
  // that row only.
  const bool one_row = spec.get_int_attribute("tiff:PhotometricInterpretation", -1) == 0 && spec.nchannels > 1;
  const int rows = one_row ? 1 : std::min(spec.height, std::max(rows_per_strip, fit / rows_per_strip * rows_per_strip));
  DecoderBuffer strip(row_bytes * static_cast<std::size_t>(rows));
  const int read = last - first + 1;
  const OIIO::stride_t out_pixel = static_cast<OIIO::stride_t>(read * sizeof(float));
  const OIIO::stride_t out_row = out_pixel * spec.width;
  for (int y = 0; y < spec.height; y += rows) {
    const int count = std::min(rows, spec.height - y);
    if (!in.read_scanlines(0, 0, spec.y + y, spec.y + y + count, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN,
                           strip.data()))
      return false;
    auto* out = reinterpret_cast<unsigned char*>(pixels) + static_cast<std::size_t>(y) * static_cast<std::size_t>(out_row);
    // Channels of one stored format at a time (OpenEXR may mix half and float).
    for (int c = first; c <= last;) {
      const OIIO::TypeDesc format = spec.channelformat(c);
      int n = 1;
      while (c + n <= last && spec.channelformat(c + n) == format) ++n;
      if (!OIIO::convert_image(n, spec.width, count, 1, strip.data() + spec.pixel_bytes(0, c, true), format,
                               static_cast<OIIO::stride_t>(pixel_bytes), static_cast<OIIO::stride_t>(row_bytes),
                               OIIO::AutoStride, out + (c - first) * sizeof(float), OIIO::TypeDesc::FLOAT, out_pixel,
                               out_row, OIIO::AutoStride))
        return false;
      c += n;
    }
  }
  return true;
}

// Where buffers are guarded (decoder_buffer.hpp), the decoders fill one of their own, copied out after.
std::optional<DecoderBuffer> guard_for(std::size_t floats) {
  if (DecoderBuffer::guarded()) return std::optional<DecoderBuffer>(std::in_place, floats * sizeof(float));
  return std::nullopt;
}

bool read_picture(void* picture, int first, int last, float* pixels, std::string& why) {
  auto& in = *static_cast<OIIO::ImageInput*>(picture);
  const std::size_t floats = static_cast<std::size_t>(in.spec().width) * static_cast<std::size_t>(in.spec().height) *
                             static_cast<std::size_t>(last - first + 1);
  auto guard = guard_for(floats);
  float* into = guard ? reinterpret_cast<float*>(guard->data()) : pixels;
  // Tiled and deep pictures keep OpenImageIO's own whole-picture read (its tile buffer is a tile).
  const bool scanlines = in.spec().tile_width == 0 && !in.spec().deep;
  const bool ok = scanlines ? read_strips(in, first, last, into)
                            : in.read_image(0, 0, first, last + 1, OIIO::TypeDesc::FLOAT, into);
  if (ok && guard) std::memcpy(pixels, into, guard->size());
  // OpenImageIO can report success for a truncated file and only log the error: ask it as well.
  why = first_line(in.geterror());
  if (ok && why.empty()) return true;
  if (why.empty()) why = "read failed";
  return false;
}

void close_picture(void* picture) {
  std::unique_ptr<OIIO::ImageInput> in(static_cast<OIIO::ImageInput*>(picture));
  if (in) in->close();
}

bool resize(const float* src, int nx, int ny, float* dst, int tx, int ty, const char* filter, std::string& why) {
  OIIO::ImageBuf in(OIIO::ImageSpec(nx, ny, 1, OIIO::TypeDesc::FLOAT), const_cast<float*>(src));
  OIIO::ImageBuf out = OIIO::ImageBufAlgo::resize(in, filter, 0.0f, OIIO::ROI(0, tx, 0, ty, 0, 1, 0, 1));
  auto guard = guard_for(static_cast<std::size_t>(tx) * static_cast<std::size_t>(ty));
  float* into = guard ? reinterpret_cast<float*>(guard->data()) : dst;
  if (out.has_error() || !out.get_pixels(OIIO::ROI(0, tx, 0, ty, 0, 1, 0, 1), OIIO::TypeDesc::FLOAT, into)) {
    why = out.geterror();
    return false;
  }
  if (guard) std::memcpy(dst, into, guard->size());
  return true;
}

bool write_png8(const std::string& path, int nx, int ny, int channels, const std::uint8_t* pixels, int tx, int ty,
                std::string& why) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(nx, ny, channels, OIIO::TypeDesc::UINT8), const_cast<std::uint8_t*>(pixels));
  OIIO::ImageBuf out = buf;
  if (tx != nx || ty != ny) {
    out = OIIO::ImageBufAlgo::resize(buf, "", 0, OIIO::ROI(0, tx, 0, ty, 0, channels, 0, 1));
    if (out.has_error()) {
      why = "cannot resize: " + out.geterror();
      return false;
    }
  }
  if (!out.write(path, OIIO::TypeDesc::UINT8, "png")) {
    why = out.geterror();
    return false;
  }
  return true;
}

bool encode_png16(int nx, int ny, const std::uint16_t* texels, std::vector<unsigned char>& png, std::string& why) {
  png.clear();
  OIIO::Filesystem::IOVecOutput proxy(png);
  auto out = OIIO::ImageOutput::create("png");
  if (!out) {
    why = "OpenImageIO cannot write PNG: " + first_line(OIIO::geterror());
    return false;
  }
  OIIO::ImageSpec spec(nx, ny, 1, OIIO::TypeDesc::UINT16);
  spec.channelnames = {"Y"};
  if (!out->set_ioproxy(&proxy) || !out->open("haptic.png", spec) || !out->write_image(OIIO::TypeDesc::UINT16, texels) ||
      !out->close()) {
    why = "OpenImageIO failed to write a 16-bit PNG: " + first_line(out->geterror());
    return false;
  }
  return true;
}

Api make_table() {
  Api a;
  a.abi = kAbi;
  a.build = SANDPAPER_IMAGE_IO_BUILD;
  a.open = open_picture;
  a.read = read_picture;
  a.close = close_picture;
  a.resize = resize;
  a.write_png8 = write_png8;
  a.encode_png16 = encode_png16;
  return a;
}

const Api kTable = make_table();

}  // namespace

#ifndef SANDPAPER_IMAGE_IO_MODULE
const Api& api() { return kTable; }
std::string provider() { return "linked"; }
#endif

}  // namespace sandpaper::compiler::image_io

#ifdef SANDPAPER_IMAGE_IO_MODULE
extern "C" __attribute__((visibility("default"))) const sandpaper::compiler::image_io::Api* sandpaper_image_io_table() {
  return &sandpaper::compiler::image_io::kTable;
}
#endif
