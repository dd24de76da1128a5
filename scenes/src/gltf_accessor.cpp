// glTF accessors read as numbers (gltf_accessor.hpp). Bytes are assembled little-endian one by one,
// as the format stores them, whatever the host, and never read before their range is checked.
#include "gltf_accessor.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

namespace sandpaper::scenes::gltf_read {
namespace {

using compiler::GltfDocument;
using compiler::gltf_index;
using compiler::gltf_member;
using compiler::gltf_optional_member;
using compiler::refuse_gltf;
using nlohmann::json;

std::size_t components_of(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

std::size_t bytes_of(int component_type) {
  switch (component_type) {
    case kByte: case kUnsignedByte: return 1;
    case kShort: case kUnsignedShort: return 2;
    case kUnsignedInt: case kFloat: return 4;
    default: return 0;
  }
}

const char* name_of(int component_type) {
  switch (component_type) {
    case kByte: return "BYTE";
    case kUnsignedByte: return "UNSIGNED_BYTE";
    case kShort: return "SHORT";
    case kUnsignedShort: return "UNSIGNED_SHORT";
    case kUnsignedInt: return "UNSIGNED_INT";
    case kFloat: return "FLOAT";
    default: return "unknown";
  }
}

// An unsigned byte count or offset in the JSON, bounded by the largest file.
std::uint64_t byte_field(const json& j, const char* key, const std::string& where) {
  const json* v = gltf_optional_member(j, key);
  if (!v) return 0;
  if (!v->is_number_unsigned() || v->get<std::uint64_t>() > compiler::kMaxGltfBytes)
    refuse_gltf("E0862", where + "." + key + " is not a byte offset up to " + std::to_string(compiler::kMaxGltfBytes >> 20) + " MiB");
  return v->get<std::uint64_t>();
}

struct Accessor {
  const json* j = nullptr;
  std::string where;  // "accessors[i]"
  int component_type = 0;
  std::size_t components = 0;
  bool normalized = false;
  std::uint64_t count = 0;
};

Accessor describe(const GltfDocument& doc, const json& index, const std::string& where, const char* type) {
  const json& accessors = gltf_member(doc.root(), "accessors", "the asset", "E0862");
  const std::size_t ai = gltf_index(index, accessors, where, "E0862");
  Accessor a;
  a.j = &accessors[ai];
  a.where = "accessors[" + std::to_string(ai) + "]";
  if (!a.j->is_object()) refuse_gltf("E0862", a.where + " is not a JSON object");
  const json& ct = gltf_member(*a.j, "componentType", a.where, "E0862");
  if (!ct.is_number_integer() || bytes_of(ct.get<int>()) == 0)
    refuse_gltf("E0862", a.where + ".componentType is not one of glTF's (5120-5123, 5125, 5126)");
  a.component_type = ct.get<int>();
  const json& t = gltf_member(*a.j, "type", a.where, "E0862");
  if (!t.is_string() || components_of(t.get<std::string>()) == 0)
    refuse_gltf("E0862", a.where + ".type is not one of glTF's (SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4)");
  if (t.get<std::string>() != type)
    refuse_gltf("E0862", where + " names " + a.where + " of type " + t.get<std::string>() + ", not " + type);
  a.components = components_of(type);
  const json& count = gltf_member(*a.j, "count", a.where, "E0862");
  if (!count.is_number_unsigned() || count.get<std::uint64_t>() == 0)
    refuse_gltf("E0862", a.where + ".count is not a positive integer");
  a.count = count.get<std::uint64_t>();
  if (const json* n = gltf_optional_member(*a.j, "normalized")) {
    if (!n->is_boolean()) refuse_gltf("E0862", a.where + ".normalized is not true or false");
    a.normalized = n->get<bool>();
  }
  return a;
}

// One component at p, little-endian, as glTF 2.0 section 3.11 maps a normalized integer.
double component(int type, bool normalized, const unsigned char* p) {
  // Only the component's own bytes are read: the last one may end its buffer.
  auto u16 = [p] { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); };
  switch (type) {
    case kByte: {
      const auto v = static_cast<std::int8_t>(p[0]);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUnsignedByte: return normalized ? p[0] / 255.0 : p[0];
    case kShort: {
      const auto v = static_cast<std::int16_t>(u16());
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUnsignedShort: return normalized ? u16() / 65535.0 : u16();
    default: {
      const std::uint32_t u32 = p[0] | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
      return type == kFloat ? static_cast<double>(std::bit_cast<float>(u32)) : static_cast<double>(u32);
    }
  }
}

// A buffer view's byte range with its stride: `bytes` long from `base`.
struct Range {
  const unsigned char* base = nullptr;
  std::uint64_t length = 0, stride = 0;
};

Range view_range(const GltfDocument& doc, const json& index, const std::string& where) {
  const GltfDocument::View v = doc.view(index, where);
  Range r{v.bytes->data() + v.offset, v.length, 0};
  const json& view = doc.root()["bufferViews"][index.get<std::size_t>()];
  if (const json* s = gltf_optional_member(view, "byteStride")) {
    // glTF: 4 to 252, a multiple of 4; read as given where it is not, the bounds still checked.
    if (!s->is_number_unsigned() || s->get<std::uint64_t>() == 0 || s->get<std::uint64_t>() > 252)
      refuse_gltf("E0862", "bufferViews[" + std::to_string(index.get<std::size_t>()) + "].byteStride is not 1 to 252 bytes");
    r.stride = s->get<std::uint64_t>();
  }
  return r;
}

std::vector<double> read(const GltfDocument& doc, const Accessor& a, std::initializer_list<int> allowed, std::size_t max_count,
                         const schema::Code type_code) {
  if (std::find(allowed.begin(), allowed.end(), a.component_type) == allowed.end())
    refuse_gltf(type_code, a.where + " is of component type " + name_of(a.component_type) + ", which Sandpaper does not read here");
  if (a.normalized && (a.component_type == kFloat || a.component_type == kUnsignedInt))
    refuse_gltf("E0862", a.where + " is normalized " + name_of(a.component_type) + ": glTF normalizes only 8- and 16-bit integers");
  if (a.count > max_count)
    refuse_gltf("E0864", a.where + " has " + std::to_string(a.count) + " elements, over what the scene's limits leave (" +
                             std::to_string(max_count) + ")",
                "split the scene, or simplify its meshes (gltf-transform simplify)");
  const std::size_t element = a.components * bytes_of(a.component_type);
  std::vector<double> out(static_cast<std::size_t>(a.count) * a.components, 0.0);
  if (const json* bv = gltf_optional_member(*a.j, "bufferView")) {
    const Range r = view_range(doc, *bv, a.where + ".bufferView");
    const std::uint64_t stride = r.stride ? r.stride : element;
    const std::uint64_t offset = byte_field(*a.j, "byteOffset", a.where);
    if (offset > r.length || stride * (a.count - 1) + element > r.length - offset)
      refuse_gltf("E0862", a.where + " (" + std::to_string(a.count) + " elements of " + std::to_string(element) + " bytes, " +
                               std::to_string(stride) + " apart, from byte " + std::to_string(offset) +
                               ") passes the end of its buffer view (" + std::to_string(r.length) + " bytes)");
    const std::size_t cbytes = bytes_of(a.component_type);
    for (std::size_t e = 0; e < a.count; ++e)
      for (std::size_t c = 0; c < a.components; ++c)
        out[e * a.components + c] = component(a.component_type, a.normalized, r.base + offset + e * stride + c * cbytes);
  }
  const json* sparse = gltf_optional_member(*a.j, "sparse");
  if (!sparse) return out;
  // Sparse substitution: `count` (index, element) pairs replace elements of the dense values.
  const std::string sw = a.where + ".sparse";
  const json& sc = gltf_member(*sparse, "count", sw, "E0862");
  if (!sc.is_number_unsigned() || sc.get<std::uint64_t>() == 0 || sc.get<std::uint64_t>() > a.count)
    refuse_gltf("E0862", sw + ".count is not 1 to the accessor's count (" + std::to_string(a.count) + ")");
  const std::uint64_t n = sc.get<std::uint64_t>();
  const json& indices = gltf_member(*sparse, "indices", sw, "E0862");
  const json& values = gltf_member(*sparse, "values", sw, "E0862");
  const json& ict = gltf_member(indices, "componentType", sw + ".indices", "E0862");
  if (!ict.is_number_integer() || (ict.get<int>() != kUnsignedByte && ict.get<int>() != kUnsignedShort && ict.get<int>() != kUnsignedInt))
    refuse_gltf("E0862", sw + ".indices.componentType is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  const int index_type = ict.get<int>();
  const Range ir = view_range(doc, gltf_member(indices, "bufferView", sw + ".indices", "E0862"), sw + ".indices.bufferView");
  const Range vr = view_range(doc, gltf_member(values, "bufferView", sw + ".values", "E0862"), sw + ".values.bufferView");
  const std::uint64_t ioff = byte_field(indices, "byteOffset", sw + ".indices");
  const std::uint64_t voff = byte_field(values, "byteOffset", sw + ".values");
  const std::uint64_t ib = bytes_of(index_type);
  if (ioff > ir.length || n * ib > ir.length - ioff) refuse_gltf("E0862", sw + ".indices pass the end of their buffer view");
  if (voff > vr.length || n * element > vr.length - voff) refuse_gltf("E0862", sw + ".values pass the end of their buffer view");
  for (std::uint64_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::uint64_t>(component(index_type, false, ir.base + ioff + k * ib));
    if (i >= a.count)
      refuse_gltf("E0862", sw + ".indices[" + std::to_string(k) + "] is " + std::to_string(i) + ", past the accessor's " +
                               std::to_string(a.count) + " elements");
    for (std::size_t c = 0; c < a.components; ++c)
      out[i * a.components + c] =
          component(a.component_type, a.normalized, vr.base + voff + k * element + c * bytes_of(a.component_type));
  }
  return out;
}

}  // namespace

std::size_t accessor_count(const GltfDocument& doc, const json& index, const std::string& where, const char* type) {
  return static_cast<std::size_t>(describe(doc, index, where, type).count);
}

std::vector<double> read_attribute(const GltfDocument& doc, const json& index, const std::string& where, const char* type,
                                   std::initializer_list<int> component_types, std::size_t max_count) {
  return read(doc, describe(doc, index, where, type), component_types, max_count, "E0862");
}

std::vector<std::uint32_t> read_indices(const GltfDocument& doc, const json& index, const std::string& where, std::size_t max_count) {
  const json& accessors = gltf_member(doc.root(), "accessors", "the asset", "E0862");
  const std::size_t ai = gltf_index(index, accessors, where, "E0862");
  const json* t = gltf_optional_member(accessors[ai], "type");
  if (!t || !t->is_string() || t->get<std::string>() != "SCALAR")
    refuse_gltf("E0863", where + " names accessors[" + std::to_string(ai) + "], which is not of type SCALAR");
  const Accessor a = describe(doc, index, where, "SCALAR");
  if (a.normalized) refuse_gltf("E0863", a.where + " holds indices but is normalized");
  const std::vector<double> v = read(doc, a, {kUnsignedByte, kUnsignedShort, kUnsignedInt}, max_count, "E0863");
  std::vector<std::uint32_t> out(v.size());
  std::transform(v.begin(), v.end(), out.begin(), [](double x) { return static_cast<std::uint32_t>(x); });
  return out;
}

}  // namespace sandpaper::scenes::gltf_read
