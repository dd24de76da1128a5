// Mesh frames and UV gradients against closed forms: a plane's UVs are affine in x and y, a sphere's
// u changes by 1 per 2 pi r of equator and its normals point along the radius.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/mesh.hpp"
#include "sandpaper/shapes/primitives.hpp"

namespace sandpaper::shapes {
namespace {

TEST(Mesh, PlaneFramesAndUvGradient) {
  const Mesh mesh = plane(0.1, 0.05, 4, 2);
  EXPECT_EQ(mesh.triangle_count(), 16u);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const TriangleFrame& f = mesh.frame(t);
    EXPECT_NEAR(glm::length(f.normal - glm::dvec3{0, 0, 1}), 0.0, 1e-15);
    // u = (x + 0.1) / 0.2, v = (y + 0.05) / 0.1: gradients (5, 0, 0) and (0, 10, 0) per metre.
    EXPECT_NEAR(glm::length(f.grad_u - glm::dvec3{5.0, 0, 0}), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(f.grad_v - glm::dvec3{0, 10.0, 0}), 0.0, 1e-12);
    // The frame is orthonormal and right-handed.
    EXPECT_NEAR(glm::dot(f.tangent, f.bitangent), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(glm::cross(f.tangent, f.bitangent) - f.normal), 0.0, 1e-15);
    EXPECT_NEAR(glm::dot(f.dual1, f.e1), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(f.dual1, f.e2), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(f.dual2, f.e2), 1.0, 1e-12);
  }
}

TEST(Mesh, SphereNormalsPointOutAndUMeasuresArcLength) {
  const double r = 0.05;
  const Mesh mesh = uv_sphere(r, 256, 128);
  EXPECT_EQ(mesh.triangle_count(), 2u * 256 * 127);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const TriangleFrame& f = mesh.frame(t);
    const auto& tri = mesh.triangles()[t];
    const glm::dvec3 centroid = (mesh.vertices()[tri[0]] + mesh.vertices()[tri[1]] + mesh.vertices()[tri[2]]) / 3.0;
    // Outward, within the facet's half-angle (pi/128 at most, at the poles' fans).
    ASSERT_GT(glm::dot(f.normal, glm::normalize(centroid)), std::cos(std::numbers::pi / 128)) << "triangle " << t;
    // Near the equator u = azimuth / 2 pi changes by 1 / (2 pi r) a metre eastward, v by 1 / (pi r)
    // a metre southward.
    if (std::abs(centroid.z) < 0.002) {
      const glm::dvec3 east = glm::normalize(glm::dvec3{-centroid.y, centroid.x, 0.0});
      EXPECT_NEAR(glm::dot(f.grad_u, east), 1.0 / (2 * std::numbers::pi * r), 1e-3 / (2 * std::numbers::pi * r));
      EXPECT_NEAR(glm::dot(f.grad_v, glm::dvec3{0, 0, -1}), 1.0 / (std::numbers::pi * r), 1e-3 / (std::numbers::pi * r));
    }
  }
}

// The servo tick reads a point's UVs from the frame alone (uv_at_origin + grad . p) and the first
// vertex from its copy: at each corner of every triangle of a sphere moved 3 m from the origin, that
// gives the corner's own UVs, from the mesh's data.
TEST(Mesh, TheFrameGivesEachCornersUvsWithoutTheVertexArrays) {
  MeshData data = uv_sphere_data(0.05, 64, 33);
  for (glm::dvec3& v : data.vertices) v += glm::dvec3{3.0, -1.0, 2.0};
  const Mesh mesh = Mesh::build_nonrt(data);
  double worst = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const TriangleFrame& f = mesh.frame(t);
    const auto& tri = data.triangles[t];
    EXPECT_EQ(mesh.vertex0(t), data.vertices[tri[0]]);
    if (glm::length(f.grad_u) == 0.0) continue;  // a pole's degenerate UVs: no gradient
    for (std::uint32_t corner : tri) {
      const glm::dvec2 uv{f.uv_at_origin.x + glm::dot(f.grad_u, data.vertices[corner]),
                          f.uv_at_origin.y + glm::dot(f.grad_v, data.vertices[corner])};
      worst = std::max(worst, glm::length(uv - data.uvs[corner]));
    }
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(Mesh, BoxFacesPointOutOrIn) {
  const Mesh out = box({0.01, 0.0, 0.0}, {0.02, 0.03, 0.04});
  const Mesh in = box({0.01, 0.0, 0.0}, {0.02, 0.03, 0.04}, true);
  ASSERT_EQ(out.triangle_count(), 12u);
  for (std::size_t t = 0; t < 12; ++t) {
    const auto& tri = out.triangles()[t];
    const glm::dvec3 centroid = (out.vertices()[tri[0]] + out.vertices()[tri[1]] + out.vertices()[tri[2]]) / 3.0;
    EXPECT_GT(glm::dot(out.frame(t).normal, centroid - glm::dvec3{0.01, 0.0, 0.0}), 0.0);
    EXPECT_NEAR(glm::length(in.frame(t).normal + out.frame(t).normal), 0.0, 1e-15);
  }
}

TEST(Mesh, NeighboursAcrossEdgesByPosition) {
  // The plane's square: (0, 1, 2) and (0, 2, 3) share the diagonal 0-2, opposite corners 1 and 2.
  const Mesh square = plane(0.1, 0.1);
  EXPECT_EQ(square.neighbour(0, 1), 1u);
  EXPECT_EQ(square.neighbour(1, 2), 0u);
  EXPECT_EQ(square.neighbour(0, 0), Mesh::kNoNeighbour);
  EXPECT_EQ(square.neighbour(1, 0), Mesh::kNoNeighbour);
  // Closed surfaces: every edge has a neighbour, across the sphere's UV seam and poles and across
  // the box's faces (whose corners are separate vertices at the same places).
  for (const Mesh& closed : {uv_sphere(0.05, 16, 8), box(glm::dvec3{0.0}, glm::dvec3{0.01})}) {
    for (std::size_t t = 0; t < closed.triangle_count(); ++t) {
      for (std::size_t c = 0; c < 3; ++c) {
        const std::uint32_t n = closed.neighbour(t, c);
        ASSERT_NE(n, Mesh::kNoNeighbour) << "triangle " << t << " corner " << c;
        EXPECT_TRUE(closed.neighbour(n, 0) == t || closed.neighbour(n, 1) == t || closed.neighbour(n, 2) == t);
      }
    }
  }
}

TEST(Mesh, RejectsBadInput) {
  MeshData bad_index{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 3}}, {}, {}};
  EXPECT_THROW(Mesh::build_nonrt(bad_index), std::invalid_argument);
  MeshData degenerate{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}, {}, {}};
  EXPECT_THROW(Mesh::build_nonrt(degenerate), std::invalid_argument);
  MeshData uv_count{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, {{0, 0}}, {}};
  EXPECT_THROW(Mesh::build_nonrt(uv_count), std::invalid_argument);
  MeshData nan{{{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}}, {{0, 1, 2}}, {}, {}};
  EXPECT_THROW(Mesh::build_nonrt(nan), std::invalid_argument);
  EXPECT_THROW(uv_sphere(0.05, 2, 8), std::invalid_argument);
  EXPECT_THROW(box({0, 0, 0}, {0.01, 0.0, 0.01}), std::invalid_argument);
}

}  // namespace
}  // namespace sandpaper::shapes
