// A glTF 2.0 asset as outside input (gltf_document.hpp): the file's JSON, counted before it is
// built, and its buffers' bytes, each size checked against a limit before it is trusted.
#include "sandpaper/compiler/gltf_document.hpp"

#include <string_view>

#include "gltf_support.hpp"
#include "sandpaper/schema/confined_path.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {
namespace {

using nlohmann::json;

// Counts values and depth while checking the syntax, so a hostile file is refused before a DOM of
// millions of small values is built.
struct Census : json::json_sax_t {
  std::size_t values = 0, depth = 0;
  bool over = false;
  std::string error;
  bool value() {
    if (++values > kMaxGltfJsonValues) over = true;
    return !over;
  }
  bool open() {
    if (++depth > kMaxGltfJsonDepth) over = true;
    return value();
  }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(); }
  bool key(string_t&) override { return true; }
  bool end_object() override { return --depth, true; }
  bool start_array(std::size_t) override { return open(); }
  bool end_array() override { return --depth, true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    error = e.what();
    return false;
  }
};

std::uint32_t u32_at(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
  return v;
}

// A binary glTF (glTF 2.0 section 4.4): a 12-byte header ("glTF", version 2, the file's length), a
// JSON chunk, and an optional BIN chunk; later chunks are ignored, as the format allows.
struct Glb {
  std::string json;
  std::optional<std::vector<unsigned char>> bin;
};
Glb split_glb(const std::string& b, const std::string& shown) {
  const std::string what = "'" + shown + "' is a binary glTF (.glb) ";
  if (b.size() < 20) refuse_gltf("E0711", what + "cut short: " + std::to_string(b.size()) + " bytes, less than its headers");
  if (u32_at(b, 4) != 2) refuse_gltf("E0711", what + "of version " + std::to_string(u32_at(b, 4)) + ", not 2");
  if (u32_at(b, 8) != b.size())
    refuse_gltf("E0711", what + "whose header says " + std::to_string(u32_at(b, 8)) + " bytes, but it has " + std::to_string(b.size()),
                "was it cut short?");
  const std::uint64_t json_length = u32_at(b, 12);
  if (u32_at(b, 16) != 0x4E4F534A) refuse_gltf("E0711", what + "whose first chunk is not JSON");
  if (json_length > b.size() - 20) refuse_gltf("E0711", what + "whose JSON chunk passes the end of the file");
  Glb g;
  g.json = b.substr(20, json_length);
  const std::uint64_t at = 20 + json_length;
  if (b.size() - at >= 8 && u32_at(b, at + 4) == 0x004E4942) {
    const std::uint64_t bin_length = u32_at(b, at);
    if (bin_length > b.size() - at - 8) refuse_gltf("E0711", what + "whose BIN chunk passes the end of the file");
    g.bin.emplace(b.begin() + static_cast<std::ptrdiff_t>(at + 8), b.begin() + static_cast<std::ptrdiff_t>(at + 8 + bin_length));
  }
  return g;
}

}  // namespace

void refuse_gltf(schema::Code code, std::string message, std::string suggestion) {
  throw GltfRefusal{std::string(code.text()), std::move(message), std::move(suggestion)};
}

const json& gltf_member(const json& j, const char* key, const std::string& where, schema::Code code) {
  if (!j.is_object()) refuse_gltf(code, where + " is not a JSON object");
  auto it = j.find(key);
  if (it == j.end()) refuse_gltf(code, where + " has no \"" + key + "\"");
  return *it;
}

const json* gltf_optional_member(const json& j, const char* key) {
  if (!j.is_object()) return nullptr;
  auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

std::size_t gltf_index(const json& j, const json& array, const std::string& where, schema::Code code) {
  if (!j.is_number_unsigned()) refuse_gltf(code, where + " is not an index (a non-negative integer)");
  const auto i = j.get<std::uint64_t>();
  if (!array.is_array() || i >= array.size())
    refuse_gltf(code, where + " is " + std::to_string(i) + ", past the end of its array (" +
                          std::to_string(array.is_array() ? array.size() : 0) + " entries)");
  return static_cast<std::size_t>(i);
}

GltfDocument GltfDocument::parse(const std::string& file_bytes, std::string shown, std::optional<std::filesystem::path> folder) {
  if (file_bytes.size() > kMaxGltfBytes)
    refuse_gltf("E0710", "'" + shown + "' is larger than the limit of " + std::to_string(kMaxGltfBytes >> 20) + " MiB for a glTF file");
  GltfDocument doc;
  doc.shown_ = std::move(shown);
  doc.folder_ = std::move(folder);
  std::optional<Glb> glb;
  if (file_bytes.size() >= 4 && file_bytes.compare(0, 4, "glTF") == 0) glb = split_glb(file_bytes, doc.shown_);
  const std::string& bytes = glb ? glb->json : file_bytes;
  Census census;
  const bool parsed = json::sax_parse(bytes, &census);
  if (census.over)
    refuse_gltf("E0711", "'" + doc.shown_ + "' has more than " + std::to_string(kMaxGltfJsonValues) +
                             " JSON values or is nested deeper than " + std::to_string(kMaxGltfJsonDepth));
  if (!parsed)
    refuse_gltf("E0711", "'" + doc.shown_ + "' is not JSON: " + (census.error.empty() ? std::string("parse error") : census.error),
                "a .gltf file is JSON; was it cut short?");
  doc.root_ = json::parse(bytes);
  if (!doc.root_.is_object()) refuse_gltf("E0712", "'" + doc.shown_ + "' is JSON but not a glTF asset (not an object)");
  const json& asset = gltf_member(doc.root_, "asset", "the asset");
  const json& version = gltf_member(asset, "version", "asset");
  if (!version.is_string() || version.get<std::string>() != "2.0")
    refuse_gltf("E0712", "asset.version is not \"2.0\": Sandpaper reads glTF 2.0");
  if (glb) doc.glb_bin_ = std::move(glb->bin);
  return doc;
}

const std::vector<unsigned char>& GltfDocument::buffer(std::size_t bi, const std::string& where) const {
  const json& buffers = gltf_member(root_, "buffers", "the asset", "E0715");
  if (bi >= buffers.size()) refuse_gltf("E0715", where + " names buffer " + std::to_string(bi) + ", which the asset does not have");
  if (auto it = buffers_.find(bi); it != buffers_.end()) return it->second;
  const std::string bw = "buffers[" + std::to_string(bi) + "]";
  const json* uri = gltf_optional_member(buffers[bi], "uri");
  if (!uri) {
    if (bi != 0 || !glb_bin_) refuse_gltf("E0715", bw + " has no uri and is not a .glb's BIN chunk");
    return *glb_bin_;
  }
  std::vector<unsigned char> data;
  if (!uri->is_string()) {
    refuse_gltf("E0715", bw + ".uri is not a string");
  } else if (const std::string& u = uri->get_ref<const std::string&>(); u.rfind("data:", 0) == 0) {
    const auto comma = u.find(',');
    const auto header = u.substr(0, comma == std::string::npos ? 0 : comma);
    auto bytes = comma == std::string::npos || header.find(";base64") == std::string::npos
                     ? std::nullopt
                     : gltf::base64_decode(std::string_view(u).substr(comma + 1));
    if (!bytes) refuse_gltf("E0715", bw + ".uri is not a base64 data URI");
    data = std::move(*bytes);
  } else {
    data = folder_file(u, bw);
  }
  if (data.size() > kMaxGltfBufferBytes - buffer_bytes_)
    refuse_gltf("E0715", "the asset's buffers hold more than " + std::to_string(kMaxGltfBufferBytes >> 20) + " MiB (at " + bw + ")",
                "a glTF file of at most " + std::to_string(kMaxGltfBytes >> 20) + " MiB has no more");
  buffer_bytes_ += data.size();
  return buffers_.emplace(bi, std::move(data)).first->second;
}

GltfDocument::View GltfDocument::view(const json& index, const std::string& where) const {
  const json& views = gltf_member(root_, "bufferViews", "the asset", "E0715");
  const std::size_t vi = gltf_index(index, views, where, "E0715");
  const std::string vw = "bufferViews[" + std::to_string(vi) + "]";
  const json& buffers = gltf_member(root_, "buffers", "the asset", "E0715");
  const std::size_t bi = gltf_index(gltf_member(views[vi], "buffer", vw, "E0715"), buffers, vw + ".buffer", "E0715");
  const std::string bw = "buffers[" + std::to_string(bi) + "]";
  auto size_field = [&](const json& j, const char* key, const std::string& w, bool required) -> std::uint64_t {
    const json* v = gltf_optional_member(j, key);
    if (!v) {
      if (required) refuse_gltf("E0715", w + " has no \"" + key + "\"");
      return 0;
    }
    if (!v->is_number_unsigned() || v->get<std::uint64_t>() > kMaxGltfBytes)
      refuse_gltf("E0715", w + "." + key + " is not a byte count up to " + std::to_string(kMaxGltfBytes >> 20) + " MiB");
    return v->get<std::uint64_t>();
  };
  const std::uint64_t offset = size_field(views[vi], "byteOffset", vw, false);
  const std::uint64_t length = size_field(views[vi], "byteLength", vw, true);
  const std::vector<unsigned char>& data = buffer(bi, vw + ".buffer");
  if (offset > data.size() || length > data.size() - offset)
    refuse_gltf("E0715", vw + " (bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) + ") passes the end of " +
                             bw + " (" + std::to_string(data.size()) + " bytes)");
  return View{&data, offset, length};
}

std::vector<unsigned char> GltfDocument::buffer_view(const json& index, const std::string& where) const {
  const View v = view(index, where);
  return std::vector<unsigned char>(v.bytes->begin() + static_cast<std::ptrdiff_t>(v.offset),
                                    v.bytes->begin() + static_cast<std::ptrdiff_t>(v.offset + v.length));
}

std::vector<unsigned char> GltfDocument::image_bytes(const json& index, const std::string& where) const {
  const json& images = gltf_member(root_, "images", "the asset", "E0715");
  const std::size_t ii = gltf_index(index, images, where, "E0715");
  const std::string iw = "images[" + std::to_string(ii) + "]";
  const json* uri = gltf_optional_member(images[ii], "uri");
  if (const json* bv = gltf_optional_member(images[ii], "bufferView"); bv && !uri) return buffer_view(*bv, iw + ".bufferView");
  if (!uri || !uri->is_string()) refuse_gltf("E0715", iw + " has neither a uri nor a bufferView");
  const std::string& u = uri->get_ref<const std::string&>();
  if (u.rfind("data:", 0) != 0) return folder_file(u, iw);
  const auto comma = u.find(',');
  auto bytes = comma == std::string::npos || u.substr(0, comma).find(";base64") == std::string::npos
                   ? std::nullopt
                   : gltf::base64_decode(std::string_view(u).substr(comma + 1));
  if (!bytes) refuse_gltf("E0715", iw + ".uri is not a base64 data URI");
  return std::move(*bytes);
}

std::vector<unsigned char> GltfDocument::folder_file(const std::string& u, const std::string& iw) const {
  const std::string shown = u.substr(0, 120);
  const auto colon = u.find(':'), slash = u.find('/');
  if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
    refuse_gltf("E0715", iw + ".uri '" + shown + "' is neither a data:image/png;base64 URI nor a file in the asset's folder",
                "embed the image, or put it beside the asset and name it by a relative path");
  const auto path = gltf::percent_decode(u);
  if (!path) refuse_gltf("E0715", iw + ".uri '" + shown + "' is not a valid relative URI (a stray '%')");
  if (!folder_)
    refuse_gltf("E0715", iw + ".uri names the file '" + shown + "', but the asset was read without its folder",
                "read the asset from its file, with its images beside it");
  std::filesystem::path full;
  try {
    full = schema::confined_path(*folder_, *path, "the asset's folder", "Sandpaper reads an asset's images from its own folder only");
  } catch (const schema::OutsideFolder& e) {
    refuse_gltf("E0715", iw + ".uri: " + e.what());
  }
  try {
    const std::string data = schema::read_input_file(full, kMaxGltfBytes);
    return std::vector<unsigned char>(data.begin(), data.end());
  } catch (const schema::InputFileError& e) {
    refuse_gltf("E0715", iw + ".uri: cannot read '" + shown + "' in the asset's folder: " + e.reason);
  }
}

}  // namespace sandpaper::compiler
