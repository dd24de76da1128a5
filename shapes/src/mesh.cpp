#include "sandpaper/shapes/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

namespace sandpaper::shapes {

void dual_basis(const glm::dvec3& e1, const glm::dvec3& e2, glm::dvec3& dual1, glm::dvec3& dual2) noexcept {
  // With G the Gram matrix of the edges, the duals are G^-1 applied to (e1, e2); they lie in the
  // plane and are blind to the normal, which is what lets a point above a triangle use them.
  const double g11 = glm::dot(e1, e1);
  const double g12 = glm::dot(e1, e2);
  const double g22 = glm::dot(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  if (!(det > 0.0)) {
    dual1 = dual2 = glm::dvec3{0.0};
    return;
  }
  dual1 = (g22 * e1 - g12 * e2) / det;
  dual2 = (g11 * e2 - g12 * e1) / det;
}

void uv_gradient(const glm::dvec3& dual1, const glm::dvec3& dual2, const glm::dvec2& duv1, const glm::dvec2& duv2,
                 glm::dvec3& grad_u, glm::dvec3& grad_v) noexcept {
  // A UV triangle of zero area maps the plane onto a line: no texture can be read through it.
  if (duv1.x * duv2.y - duv1.y * duv2.x == 0.0) {
    grad_u = grad_v = glm::dvec3{0.0};
    return;
  }
  grad_u = duv1.x * dual1 + duv2.x * dual2;
  grad_v = duv1.y * dual1 + duv2.y * dual2;
}

Mesh Mesh::build_nonrt(MeshData data) {
  const std::size_t nv = data.vertices.size();
  const std::size_t nt = data.triangles.size();
  if (!data.uvs.empty() && data.uvs.size() != nv) {
    throw std::invalid_argument("mesh: " + std::to_string(data.uvs.size()) + " UVs for " + std::to_string(nv) +
                                " vertices");
  }
  if (!data.materials.empty() && data.materials.size() != nt) {
    throw std::invalid_argument("mesh: " + std::to_string(data.materials.size()) + " materials for " +
                                std::to_string(nt) + " triangles");
  }
  for (std::size_t i = 0; i < nv; ++i) {
    const glm::dvec3& v = data.vertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      throw std::invalid_argument("mesh: vertex " + std::to_string(i) + " is not finite");
    }
  }
  Mesh mesh;
  mesh.frames_.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const Triangle& tri = data.triangles[t];
    for (std::uint32_t index : tri) {
      if (index >= nv) {
        throw std::invalid_argument("mesh: triangle " + std::to_string(t) + " names vertex " + std::to_string(index) +
                                    " of " + std::to_string(nv));
      }
    }
    TriangleFrame& f = mesh.frames_[t];
    const glm::dvec3& v0 = data.vertices[tri[0]];
    f.v0 = v0;
    f.e1 = data.vertices[tri[1]] - v0;
    f.e2 = data.vertices[tri[2]] - v0;
    const glm::dvec3 e3 = data.vertices[tri[2]] - data.vertices[tri[1]];
    const glm::dvec3 c = glm::cross(f.e1, f.e2);
    const double area2 = glm::length(c);
    // 2 area = |a||b| sin(angle) for each pair of edges: the smallest sine is area2 over the
    // product of the two longest edges.
    double l1 = glm::length(f.e1), l2 = glm::length(f.e2), l3 = glm::length(e3);
    const double longest_pair = std::max({l1 * l2, l2 * l3, l1 * l3});
    if (!(area2 > 1e-12 * longest_pair)) {
      throw std::invalid_argument("mesh: triangle " + std::to_string(t) + " is degenerate");
    }
    f.normal = c / area2;
    f.tangent = f.e1 / l1;
    f.bitangent = glm::cross(f.normal, f.tangent);
    dual_basis(f.e1, f.e2, f.dual1, f.dual2);
    if (!data.uvs.empty()) {
      const glm::dvec2& uv0 = data.uvs[tri[0]];
      uv_gradient(f.dual1, f.dual2, data.uvs[tri[1]] - uv0, data.uvs[tri[2]] - uv0, f.grad_u, f.grad_v);
      f.uv_at_origin = uv0 - glm::dvec2{glm::dot(f.grad_u, v0), glm::dot(f.grad_v, v0)};
    }
  }
  // Edge adjacency by position: the proxy walks from a triangle to its neighbour when it slides
  // across a flat seam, and an index-based match would stop at every UV seam.
  mesh.neighbours_.assign(nt, {kNoNeighbour, kNoNeighbour, kNoNeighbour});
  using Point = std::array<double, 3>;
  struct Side {
    std::uint32_t triangle[2];
    std::uint32_t corner[2];
    int count;
  };
  std::map<std::pair<Point, Point>, Side> sides;
  auto point = [&](std::uint32_t v) { return Point{data.vertices[v].x, data.vertices[v].y, data.vertices[v].z}; };
  for (std::size_t t = 0; t < nt; ++t) {
    for (std::uint32_t corner = 0; corner < 3; ++corner) {
      Point a = point(data.triangles[t][(corner + 1) % 3]), b = point(data.triangles[t][(corner + 2) % 3]);
      if (b < a) std::swap(a, b);
      Side& side = sides.try_emplace({a, b}, Side{{0, 0}, {0, 0}, 0}).first->second;
      if (side.count < 2) {
        side.triangle[side.count] = static_cast<std::uint32_t>(t);
        side.corner[side.count] = corner;
      }
      ++side.count;
    }
  }
  // An edge of one triangle is open; of three or more, it has no one neighbour: both left unset.
  for (const auto& [edge, side] : sides) {
    if (side.count != 2) continue;
    mesh.neighbours_[side.triangle[0]][side.corner[0]] = side.triangle[1];
    mesh.neighbours_[side.triangle[1]][side.corner[1]] = side.triangle[0];
  }
  mesh.materials_ = std::move(data.materials);
  mesh.materials_.resize(nt, 0);
  mesh.max_material_ = mesh.materials_.empty() ? 0 : *std::max_element(mesh.materials_.begin(), mesh.materials_.end());
  mesh.vertices_ = std::move(data.vertices);
  mesh.triangles_ = std::move(data.triangles);
  mesh.uvs_ = std::move(data.uvs);
  return mesh;
}

}  // namespace sandpaper::shapes
