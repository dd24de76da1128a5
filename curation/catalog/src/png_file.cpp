#include "png_file.hpp"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <vector>

namespace sandpaper::catalog {
namespace {

// libpng reports an error by longjmp out of its call: what is in scope between setjmp and the
// jump must need no destructor, so this part is plain C over what the caller prepared.
struct Failure {
  char message[256] = {};
};

void on_error(png_structp png, png_const_charp message) {
  auto* f = static_cast<Failure*>(png_get_error_ptr(png));
  std::snprintf(f->message, sizeof f->message, "%s", message);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

bool encode(std::FILE* out, int nx, int ny, int type, png_bytepp rows, Failure& failure) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &failure, on_error, on_warning);
  if (!png) {
    std::snprintf(failure.message, sizeof failure.message, "libpng cannot start");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    if (!failure.message[0]) std::snprintf(failure.message, sizeof failure.message, "libpng failed");
    return false;
  }
  png_init_io(png, out);
  png_set_IHDR(png, info, static_cast<png_uint_32>(nx), static_cast<png_uint_32>(ny), 8, type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

bool write_png_file(const std::filesystem::path& file, int nx, int ny, int channels, const std::uint8_t* pixels,
                    std::string& why) {
  static constexpr int kTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGBA};
  if (nx <= 0 || ny <= 0 || channels < 1 || channels > 4) {
    why = "no PNG of " + std::to_string(nx) + " x " + std::to_string(ny) + " px and " + std::to_string(channels) + " channels";
    return false;
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(ny));
  const std::size_t stride = static_cast<std::size_t>(nx) * static_cast<std::size_t>(channels);
  for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = const_cast<png_bytep>(pixels + y * stride);
  std::FILE* out = std::fopen(file.c_str(), "wb");
  if (!out) {
    why = std::strerror(errno);
    return false;
  }
  Failure failure;
  const bool encoded = encode(out, nx, ny, kTypes[channels - 1], rows.data(), failure);
  const bool closed = std::fclose(out) == 0;
  if (encoded && closed) return true;
  why = encoded ? std::string(std::strerror(errno)) : std::string(failure.message);
  return false;
}

}  // namespace sandpaper::catalog
