#pragma once
// A bounding-volume hierarchy over a mesh's triangles: axis-aligned boxes, built once off the
// servo thread, queried on it without allocating (a fixed explicit stack), so that a contact costs
// about log2(triangles) box tests rather than one test a triangle.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "sandpaper/shapes/mesh.hpp"
#include "sandpaper/shapes/segment_triangle.hpp"

namespace sandpaper::shapes {

// The first crossing of a segment a -> b: t in [0, 1] along it, the point a + t (b - a) (m), and
// the mesh's triangle index.
struct SegmentHit {
  double t = 0.0;
  glm::dvec3 point_m{0.0};
  std::uint32_t triangle = 0;
};

class Bvh {
 public:
  // A triangle as the leaves keep it: corner v0 and edges e1, e2 (m), and its mesh index.
  struct LeafTriangle {
    glm::dvec3 v0{0.0};
    glm::dvec3 e1{0.0};
    glm::dvec3 e2{0.0};
    std::uint32_t index = 0;
  };

  static constexpr std::size_t kMaxLeafTriangles = 4;
  // The traversal stack; a median split keeps the depth near log2(triangles / 4) + 1, so 64
  // levels hold any mesh that fits in memory (the build checks it).
  static constexpr std::size_t kStackSize = 64;

  // Median split on the longest axis of the triangles' centroids, O(n log n), off the servo thread.
  // Copies each triangle's v0, e1, e2 in leaf order, so the mesh need not outlive the tree.
  // Throws std::length_error if the tree would be deeper than the stack (not for real meshes).
  static Bvh build_nonrt(const Mesh& mesh);

  // The nearest triangle crossed by the segment a -> b (m), skipping the triangle indices in
  // excluded (a short list: the renderer's active constraints). Ties in t go to the lowest index,
  // so the answer does not depend on the tree's shape. Real time: no allocation, no exceptions.
  // nodes_visited, when given, counts the nodes whose box was entered (for cost measurements).
  std::optional<SegmentHit> first_hit_rt(const glm::dvec3& a, const glm::dvec3& b,
                                          std::span<const std::uint32_t> excluded = {},
                                          Facing facing = Facing::both,
                                          std::uint32_t* nodes_visited = nullptr) const noexcept;

  // The triangles whose own box, padded as the nodes' are, overlaps the box lo..hi (m), in leaf
  // order, written to out: their count, or nullopt when there are more than out holds (out's
  // contents are then unspecified). Any segment within lo..hi that crosses a triangle crosses one
  // of these, so a query over them alone answers as first_hit_rt would. Real time.
  std::optional<std::size_t> gather_rt(const glm::dvec3& lo, const glm::dvec3& hi, std::span<LeafTriangle> out) const noexcept;

  // How far every box reaches past what it bounds (m): the edge tolerance's reach, and rounding.
  double pad_m() const noexcept { return pad_; }
  std::size_t node_count() const noexcept { return nodes_.size(); }
  std::size_t depth() const noexcept { return depth_; }
  std::size_t triangle_count() const noexcept { return triangles_.size(); }

 private:
  struct Node {
    glm::dvec3 lo{0.0};
    std::uint32_t first = 0;  // leaf: its first triangle; inner: its right child (left is next)
    glm::dvec3 hi{0.0};
    std::uint32_t count = 0;  // triangles in a leaf; 0 for an inner node
  };
  struct Builder;

  std::vector<Node> nodes_;
  std::vector<LeafTriangle> triangles_;
  std::size_t depth_ = 0;
  double pad_ = 0.0;  // how far every box reaches past what it bounds (m)
};

}  // namespace sandpaper::shapes
