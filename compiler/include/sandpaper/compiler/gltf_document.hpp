#pragma once
// A glTF 2.0 asset read as outside input (docs/GLTF.md, "Import" and "Scenes (3-D)"): the JSON of a
// .gltf, or of a .glb with its BIN chunk, parsed under the limits below, and the bytes of its
// buffers, buffer views and images, from the BIN chunk, base64 data URIs or files confined to the
// asset's own folder. The patch importer (gltf_import.hpp) and the scene reader
// (scenes/gltf_scene.hpp) both read through it, so both refuse the same inputs with the same codes.
// Part of sandpaper_gltf (SANDPAPER_GLTF).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/schema/diagnostic_codes.hpp"

namespace sandpaper::compiler {

// A glTF file: 128 MiB (a 4096 x 4096 16-bit texture is at most 43 MiB of base64).
inline constexpr std::size_t kMaxGltfBytes = std::size_t{128} << 20;
// JSON values in the asset (a shipped workspace has a few hundred) and their nesting depth.
inline constexpr std::size_t kMaxGltfJsonValues = std::size_t{1} << 20;
inline constexpr std::size_t kMaxGltfJsonDepth = 64;
// Bytes of buffers decoded from data URIs or read from files, over the whole asset: twice a file's
// limit, so that an asset naming one large file from many buffers is refused, not read many times.
inline constexpr std::uint64_t kMaxGltfBufferBytes = std::uint64_t{256} << 20;

// The first problem found in an asset: a registered code, what (naming the JSON place), and how to
// fix it. The readers throw it and catch it once at their top, where it becomes one diagnostic.
struct GltfRefusal {
  std::string code, message, suggestion;
};
[[noreturn]] void refuse_gltf(schema::Code code, std::string message, std::string suggestion = {});

// JSON access that names the place of anything missing or mistyped: `where` has no `key` (or is not
// an object) is refused with `code`.
const nlohmann::json& gltf_member(const nlohmann::json& j, const char* key, const std::string& where,
                                  schema::Code code = "E0712");
const nlohmann::json* gltf_optional_member(const nlohmann::json& j, const char* key);
// `j` as an index into `array`, refused with `code` unless it is a non-negative integer below its size.
std::size_t gltf_index(const nlohmann::json& j, const nlohmann::json& array, const std::string& where, schema::Code code);

// A texture of values, one per texel (MPEG_haptic_material's stiffness or friction, written by any
// tool): the first channel (grey, or red) of an 8- or 16-bit greyscale, grey-alpha, RGB or RGBA
// PNG without interlacing, normalized to 0..1 as a glTF sampler reads it (value / 255, / 65535).
struct GltfValueImage {
  int nx = 0, ny = 0;
  int bit_depth = 0;          // 8 or 16
  std::vector<float> values;  // row-major, row 0 the top row
};
// Decodes `bytes` with the haptic textures' own PNG decoder (every chunk's CRC checked, the image data
// inflated to exactly the size its header promises), refusing more than `max_pixels` texels from the
// header before any pixel is allocated. nullopt with `why` (one line) for another kind or a broken file.
std::optional<GltfValueImage> decode_gltf_value_png(const std::vector<unsigned char>& bytes, long long max_pixels, std::string& why);

class GltfDocument {
 public:
  // Parses a .gltf's JSON, or a .glb (bytes starting "glTF"), shown in messages as `shown`; images
  // and buffers named by relative URIs are read from `folder` (none: only embedded ones). Throws
  // GltfRefusal: E0710 over kMaxGltfBytes; E0711 not JSON, a .glb whose header or chunks do not hold
  // together (glTF 2.0 section 4.4), or over kMaxGltfJsonValues values or kMaxGltfJsonDepth deep
  // (counted before the document is built); E0712 not a JSON object, or no asset.version "2.0".
  static GltfDocument parse(const std::string& bytes, std::string shown, std::optional<std::filesystem::path> folder);

  const nlohmann::json& root() const noexcept { return root_; }
  const std::string& shown() const noexcept { return shown_; }

  // A byte range of a buffer: buffer view `index` as its buffer's bytes, offset and length (checked
  // to lie inside the buffer). The bytes are kept by the document. Throws GltfRefusal E0715 for a bad
  // view or buffer index, a byte count that is not one, a buffer that cannot be read, or a view past
  // its buffer's end. The view's byteStride is left to the caller (an image has none).
  struct View {
    const std::vector<unsigned char>* bytes = nullptr;
    std::uint64_t offset = 0, length = 0;
  };
  View view(const nlohmann::json& index, const std::string& where) const;
  // A copy of the view's bytes.
  std::vector<unsigned char> buffer_view(const nlohmann::json& index, const std::string& where) const;
  // A file named by a relative, percent-encoded URI (RFC 3986), read from the asset's own folder with
  // symbolic links followed and nothing outside it read (schema::confined_path); `where` names the
  // JSON place. Throws GltfRefusal E0715 for another scheme, an absolute path, a path leading out, a
  // missing file, or an asset read without its folder.
  std::vector<unsigned char> folder_file(const std::string& uri, const std::string& where) const;
  // The bytes of images[`index`] (checked to be an index): its buffer view, a base64 data URI of any
  // media type, or a file in the asset's folder. Throws GltfRefusal E0715.
  std::vector<unsigned char> image_bytes(const nlohmann::json& index, const std::string& where) const;

 private:
  // Buffer `index`, decoded once: the .glb's BIN chunk (buffer 0 without a uri), a base64 data URI,
  // or a file in the asset's folder (those two within kMaxGltfBufferBytes in all).
  const std::vector<unsigned char>& buffer(std::size_t index, const std::string& where) const;

  nlohmann::json root_;
  std::string shown_;
  std::optional<std::filesystem::path> folder_;
  std::optional<std::vector<unsigned char>> glb_bin_;
  mutable std::map<std::size_t, std::vector<unsigned char>> buffers_;
  mutable std::uint64_t buffer_bytes_ = 0;
};

}  // namespace sandpaper::compiler
