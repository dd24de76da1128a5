#pragma once
// A triangle mesh as the renderer feels it: positions in metres, outward faces wound
// counter-clockwise, and per triangle everything the servo tick would otherwise recompute.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sandpaper::shapes {

using Triangle = std::array<std::uint32_t, 3>;

// Precomputed per triangle so that contact and texture lookups on the servo thread are dot
// products only. e1 = v1 - v0, e2 = v2 - v0 (m); normal = unit e1 x e2 (the outside); tangent =
// unit e1 and bitangent = normal x tangent complete a right-handed orthonormal frame. What the
// servo tick reads comes first and the struct is one cache line aligned, so that a triangle's
// lookups touch three lines, not four, and never a vertex or index array.
struct alignas(64) TriangleFrame {
  glm::dvec3 normal{0.0};
  glm::dvec3 v0{0.0};  // the first vertex (m), a copy of the mesh's
  // The dual basis of (e1, e2) in the plane (1/m): the barycentric coordinates of a point x are
  // b1 = dot(dual1, x - v0), b2 = dot(dual2, x - v0), b0 = 1 - b1 - b2, whatever its height.
  glm::dvec3 dual1{0.0};
  glm::dvec3 dual2{0.0};
  // The UV gradient, a 2x3 map as two rows (1/m): a displacement s in the triangle's plane changes
  // the texture coordinates by (du, dv) = (dot(grad_u, s), dot(grad_v, s)); both rows lie in the
  // plane. Zero when the mesh has no UVs, or the triangle's UVs are degenerate (zero UV area).
  glm::dvec3 grad_u{0.0};
  glm::dvec3 grad_v{0.0};
  // The texture coordinates the triangle's UV map gives the scene's origin, so that a point p on
  // (or above) the plane has u = uv_at_origin.x + dot(grad_u, p), v likewise, without reading a
  // vertex. Zero when grad_u and grad_v are.
  glm::dvec2 uv_at_origin{0.0};
  glm::dvec3 tangent{0.0};
  glm::dvec3 bitangent{0.0};
  glm::dvec3 e1{0.0};
  glm::dvec3 e2{0.0};
};

// What a mesh is made from, before its frames are computed. uvs is empty or one per vertex;
// materials is empty (all 0) or one index per triangle into the renderer's material table.
struct MeshData {
  std::vector<glm::dvec3> vertices;  // m
  std::vector<Triangle> triangles;   // indices into vertices, counter-clockwise seen from outside
  std::vector<glm::dvec2> uvs;       // texture coordinates, per vertex, optional
  std::vector<std::uint16_t> materials;
};

class Mesh {
 public:
  // Checks and precomputes, off the servo thread. Throws std::invalid_argument on an index out of
  // range, uvs or materials of the wrong count, a non-finite vertex, or a degenerate triangle
  // (sine of its smallest angle below 1e-12), naming the triangle.
  static Mesh build_nonrt(MeshData data);

  std::size_t triangle_count() const noexcept { return triangles_.size(); }
  std::size_t vertex_count() const noexcept { return vertices_.size(); }
  bool has_uvs() const noexcept { return !uvs_.empty(); }

  std::span<const glm::dvec3> vertices() const noexcept { return vertices_; }
  std::span<const Triangle> triangles() const noexcept { return triangles_; }
  std::span<const glm::dvec2> uvs() const noexcept { return uvs_; }
  std::span<const TriangleFrame> frames() const noexcept { return frames_; }

  const glm::dvec3& vertex0(std::size_t triangle) const noexcept { return frames_[triangle].v0; }
  // The triangle across the edge opposite corner `corner` (0..2) of `triangle`, matched by vertex
  // positions (seams repeat vertices); kNoNeighbour on an open or non-manifold edge.
  static constexpr std::uint32_t kNoNeighbour = 0xffffffffu;
  std::uint32_t neighbour(std::size_t triangle, std::size_t corner) const noexcept {
    return neighbours_[triangle][corner];
  }
  const TriangleFrame& frame(std::size_t triangle) const noexcept { return frames_[triangle]; }
  std::uint16_t material(std::size_t triangle) const noexcept { return materials_[triangle]; }
  std::uint16_t max_material() const noexcept { return max_material_; }

 private:
  std::vector<glm::dvec3> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<glm::dvec2> uvs_;
  std::vector<std::uint16_t> materials_;  // one per triangle, always filled
  std::vector<TriangleFrame> frames_;
  std::vector<std::array<std::uint32_t, 3>> neighbours_;
  std::uint16_t max_material_ = 0;
};

// The dual basis of two edges (see TriangleFrame); zero when they are parallel.
void dual_basis(const glm::dvec3& e1, const glm::dvec3& e2, glm::dvec3& dual1, glm::dvec3& dual2) noexcept;

// The UV gradient rows of one triangle from its dual basis and its UV differences (uv1 - uv0,
// uv2 - uv0): grad = duv1 dual1 + duv2 dual2, so a displacement by e1 changes the UVs by duv1.
void uv_gradient(const glm::dvec3& dual1, const glm::dvec3& dual2, const glm::dvec2& duv1, const glm::dvec2& duv2,
                 glm::dvec3& grad_u, glm::dvec3& grad_v) noexcept;

}  // namespace sandpaper::shapes
