#pragma once
// glTF accessors (glTF 2.0 section 3.6) read as numbers: an attribute's elements as doubles, a
// primitive's indices as 32-bit integers. Outside input: every offset, stride and count is checked
// against its buffer view before a byte is read, and a count against the caller's limit before
// anything is allocated. Private to the scenes library.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/gltf_document.hpp"

namespace sandpaper::scenes::gltf_read {

// Component types (glTF 2.0 section 3.6.2.2).
inline constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
                     kFloat = 5126;

// Accessor `index`'s element count, after checking it is an accessor of element type `type` ("VEC3")
// with a count of at least 1. Refuses (compiler::GltfRefusal) with E0862; `where` names the JSON
// place that holds the index.
std::size_t accessor_count(const compiler::GltfDocument& doc, const nlohmann::json& index, const std::string& where,
                           const char* type);

// Its elements, components in order, as doubles (count * components values), with sparse
// substitution (section 3.6.2.3); an accessor without a buffer view is zeros, as the format says. A
// normalized integer is read as glTF maps it to [-1, 1] or [0, 1], a non-normalized one as its value
// (KHR_mesh_quantization). Refused with E0864 for a count over `max_count`, before any allocation;
// E0862 for a component type not in `component_types`, a normalized float or 32-bit integer, or
// bytes outside the buffer view; E0715 for a buffer view or buffer that cannot be read.
std::vector<double> read_attribute(const compiler::GltfDocument& doc, const nlohmann::json& index, const std::string& where,
                                   const char* type, std::initializer_list<int> component_types, std::size_t max_count);

// A primitive's indices: SCALAR of unsigned byte, short or int, not normalized (E0863 otherwise).
std::vector<std::uint32_t> read_indices(const compiler::GltfDocument& doc, const nlohmann::json& index, const std::string& where,
                                        std::size_t max_count);

}  // namespace sandpaper::scenes::gltf_read
