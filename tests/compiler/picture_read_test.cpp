// The picture table's read (compiler/image_io/oiio_backend.cpp) takes scanline pictures in strips in
// their own format and converts them itself; it must give exactly the floats OpenImageIO's own
// whole-picture read gives, for every stored type, mixed channel types, an offset data window, strips
// that split a TIFF strip, tiles, and any channel range.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <utility>
#include <string>
#include <vector>

#include "sandpaper/compiler/image_io.hpp"
#include "test_support.hpp"

namespace {

namespace io = sandpaper::compiler::image_io;

struct Picture {
  std::string name;
  int width, height, channels;
  OIIO::TypeDesc format;
  std::vector<OIIO::TypeDesc> channel_formats;  // empty: all `format`
  int x = 0, y = 0;                               // data window origin
  int tile = 0;                                   // tile side; 0 for scanlines
  int rows_per_strip = 0;                         // TIFF only; 0 for the writer's choice
};

// Writes a picture whose every channel of every pixel differs, as float values OpenImageIO quantises
// to the stored type.
void write(const std::string& path, const Picture& p) {
  OIIO::ImageSpec spec(p.width, p.height, p.channels, p.format);
  spec.x = p.x;
  spec.y = p.y;
  if (!p.channel_formats.empty()) spec.channelformats = p.channel_formats;
  if (p.tile) spec.tile_width = spec.tile_height = p.tile;
  if (p.rows_per_strip) spec.attribute("tiff:RowsPerStrip", p.rows_per_strip);
  std::vector<float> v(static_cast<std::size_t>(p.width) * p.height * p.channels);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>((i * 7919) % 1009) / 1009.0f;
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  ASSERT_TRUE(out->open(path, spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, v.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

std::vector<float> reference(const std::string& path, int first, int last) {
  // As the table opens pictures: heights as stored, never premultiplied by alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  const auto& s = in->spec();
  std::vector<float> v(static_cast<std::size_t>(s.width) * s.height * (last - first + 1));
  EXPECT_TRUE(in->read_image(0, 0, first, last + 1, OIIO::TypeDesc::FLOAT, v.data())) << in->geterror();
  return v;
}

TEST(PictureRead, StripsGiveOpenImageIOsOwnFloatsForEveryLayout) {
  const std::string dir = sandpaper::test::temp_dir("picture-read");
  using T = OIIO::TypeDesc;
  const std::vector<T> scan{};
  const std::vector<Picture> pictures = {
      // name, width, height, channels, type, channel types, data window x, y, tile, TIFF rows a strip
      {"grey8.png", 37, 301, 1, T::UINT8, scan, 0, 0, 0, 0},
      {"rgba16.png", 53, 90, 4, T::UINT16, scan, 0, 0, 0, 0},
      {"rgba16.tif", 41, 200, 4, T::UINT16, scan, 0, 0, 0, 3},
      {"float.tif", 300, 5000, 2, T::FLOAT, scan, 0, 0, 0, 0},  // several 1 MiB strips
      {"mixed.exr", 64, 70, 4, T::HALF, {T::HALF, T::FLOAT, T::HALF, T::FLOAT}, 10, 7, 0, 0},
      {"tiled.exr", 50, 45, 3, T::HALF, scan, 0, 0, 16, 0},
      {"tiled.tif", 50, 45, 3, T::UINT8, scan, 0, 0, 16, 0},
      {"rgb.jpg", 33, 17, 3, T::UINT8, scan, 0, 0, 0, 0},
      {"rgba.tga", 20, 21, 4, T::UINT8, scan, 0, 0, 0, 0},
      {"rgb.hdr", 19, 23, 3, T::FLOAT, scan, 0, 0, 0, 0},
  };
  for (const auto& p : pictures) {
    const std::string path = dir + "/" + p.name;
    write(path, p);
    io::PictureHeader header;
    std::string why;
    void* picture = io::api().open(path, header, why);
    ASSERT_NE(picture, nullptr) << p.name << ": " << why;
    ASSERT_EQ(header.width, p.width) << p.name;
    ASSERT_EQ(header.height, p.height) << p.name;
    const int n = header.channels;
    io::api().close(picture);
    // Each range on a freshly opened picture, as the compiler reads one.
    for (const auto& [first, last] : {std::pair{0, n - 1}, std::pair{n - 1, n - 1}, std::pair{n > 2 ? 1 : 0, n > 2 ? 2 : 0}}) {
      picture = io::api().open(path, header, why);
      ASSERT_NE(picture, nullptr) << p.name << ": " << why;
      std::vector<float> got(static_cast<std::size_t>(header.width) * header.height * (last - first + 1), -1.0f);
      ASSERT_TRUE(io::api().read(picture, first, last, got.data(), why)) << p.name << ": " << why;
      io::api().close(picture);
      const auto want = reference(path, first, last);
      ASSERT_EQ(got.size(), want.size()) << p.name;
      std::size_t differ = 0;
      for (std::size_t i = 0; i < got.size(); ++i) differ += !(got[i] == want[i]);
      EXPECT_EQ(differ, 0u) << p.name << ", channels " << first << ".." << last;
    }
  }
}

// A TIFF written byte by byte (OpenImageIO writes no MinIsWhite): `channels` 8-bit samples a pixel,
// contiguous, deflate strips of `rows_per_strip` rows, photometric MinIsWhite (0). Stored sample
// (x, y, c) = stored_sample(x, y, c); read, it means 255 minus that.
unsigned stored_sample(int x, int y, int c) { return static_cast<unsigned>(x * 7 + y * 13 + c * 50) % 256u; }

void write_miniswhite_tiff(const std::string& path, int width, int height, int channels, int rows_per_strip) {
  std::string body;  // strips, then the arrays the directory points at
  auto u16 = [](std::string& s, unsigned v) { s += static_cast<char>(v & 0xff); s += static_cast<char>(v >> 8); };
  auto u32 = [&](std::string& s, std::uint32_t v) { u16(s, v & 0xffff); u16(s, v >> 16); };
  std::vector<std::uint32_t> offsets, counts;
  for (int y0 = 0; y0 < height; y0 += rows_per_strip) {
    std::string raw;
    for (int y = y0; y < std::min(height, y0 + rows_per_strip); ++y)
      for (int x = 0; x < width; ++x)
        for (int c = 0; c < channels; ++c) raw += static_cast<char>(stored_sample(x, y, c));
    uLongf size = compressBound(static_cast<uLong>(raw.size()));
    std::string packed(size, '\0');
    ASSERT_EQ(compress(reinterpret_cast<Bytef*>(packed.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                       static_cast<uLong>(raw.size())),
              Z_OK);
    offsets.push_back(static_cast<std::uint32_t>(8 + body.size()));
    counts.push_back(static_cast<std::uint32_t>(size));
    body.append(packed.data(), size);
    if (body.size() % 2) body += '\0';
  }
  auto array32 = [&](const std::vector<std::uint32_t>& v) {
    const auto at = static_cast<std::uint32_t>(8 + body.size());
    for (auto x : v) u32(body, x);
    return at;
  };
  const std::uint32_t bits_at = static_cast<std::uint32_t>(8 + body.size());
  for (int c = 0; c < channels; ++c) u16(body, 8);
  const std::uint32_t offsets_at = array32(offsets), counts_at = array32(counts);
  struct Entry { unsigned tag, type; std::uint32_t count, value; };  // type 3 SHORT, 4 LONG
  const std::vector<Entry> entries = {
      {256, 4, 1, static_cast<std::uint32_t>(width)}, {257, 4, 1, static_cast<std::uint32_t>(height)},
      {258, 3, static_cast<std::uint32_t>(channels), bits_at}, {259, 3, 1, 8 /* deflate */},
      {262, 3, 1, 0 /* MinIsWhite */}, {273, 4, static_cast<std::uint32_t>(offsets.size()), offsets_at},
      {277, 3, 1, static_cast<std::uint32_t>(channels)}, {278, 4, 1, static_cast<std::uint32_t>(rows_per_strip)},
      {279, 4, static_cast<std::uint32_t>(counts.size()), counts_at}, {284, 3, 1, 1 /* contiguous */}};
  ASSERT_GT(channels, 2);     // the bits array lies outside its entry
  ASSERT_GT(offsets.size(), 1u);  // so do the strip arrays
  std::string file = "II*";
  file += '\0';
  u32(file, static_cast<std::uint32_t>(8 + body.size()));
  file += body;
  u16(file, static_cast<unsigned>(entries.size()));
  for (const auto& e : entries) {
    u16(file, e.tag);
    u16(file, e.type);
    u32(file, e.count);
    if (e.type == 3 && e.count == 1) {
      u16(file, e.value);
      u16(file, 0);
    } else {
      u32(file, e.value);
    }
  }
  u32(file, 0);
  std::ofstream(path, std::ios::binary) << file;
}

// F41: OpenImageIO 2.4 inverted a MinIsWhite deflate strip's values over the strip times its channel
// count, writing past the buffer it was given. Where decoder buffers are guarded (the test suite sets
// SANDPAPER_GUARD_DECODER_BUFFERS=1), that stops this test with SIGSEGV; unguarded it can overwrite
// the heap. Read a row at a time, every value is the inverted sample.
TEST(PictureRead, MinIsWhiteDeflateTiffOfNineChannelsStaysInsideItsBufferWithEveryValueInverted) {
  const std::string path = sandpaper::test::temp_dir("picture-read-miniswhite") + "/white9.tif";
  const int width = 16, height = 64, channels = 9;
  write_miniswhite_tiff(path, width, height, channels, 16);
  for (const auto& [first, last] : {std::pair{0, channels - 1}, std::pair{4, 4}}) {
    io::PictureHeader header;
    std::string why;
    void* picture = io::api().open(path, header, why);
    ASSERT_NE(picture, nullptr) << why;
    ASSERT_EQ(header.channels, channels);
    const int read = last - first + 1;
    std::vector<float> got(static_cast<std::size_t>(width) * height * read, -1.0f);
    ASSERT_TRUE(io::api().read(picture, first, last, got.data(), why)) << why;
    io::api().close(picture);
    std::size_t differ = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        for (int c = first; c <= last; ++c) {
          const float want = static_cast<float>(255u - stored_sample(x, y, c)) / 255.0f;
          const float v = got[(static_cast<std::size_t>(y) * width + x) * read + (c - first)];
          differ += !(std::fabs(v - want) < 1e-6f);
        }
    EXPECT_EQ(differ, 0u) << "channels " << first << ".." << last;
  }
}

}  // namespace
