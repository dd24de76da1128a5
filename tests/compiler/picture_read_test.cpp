// The picture table's read (compiler/image_io/oiio_backend.cpp) takes scanline pictures in strips in
// their own format and converts them itself; it must give exactly the floats OpenImageIO's own
// whole-picture read gives, for every stored type, mixed channel types, an offset data window, strips
// that split a TIFF strip, tiles, and any channel range.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstdint>
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

}  // namespace
