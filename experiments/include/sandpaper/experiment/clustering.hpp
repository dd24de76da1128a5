#pragma once
// Agglomerative hierarchical clustering of a distance matrix, as the thesis analysed its sorts
// (Minsky 1995, 6.3: single linkage on "number of sorts in which two stimuli share a group"), with
// average linkage beside it. Ties merge the pair with the smallest indices first, so results do
// not depend on the platform.
#include <cstddef>
#include <vector>

namespace sandpaper::experiment {

enum class Linkage {
  Single,   // distance between clusters = the smallest distance between their members
  Average,  // = the mean distance over all pairs of members (UPGMA)
};

// One merge: clusters `a` and `b` joined at `height`. Ids below n are the leaves (the matrix's
// rows); n + k is the cluster made by merge k. `size` counts its leaves.
struct Merge {
  int a = 0, b = 0;
  double height = 0;
  int size = 0;
};

// n - 1 merges, in order of height. `distance` must be square, symmetric, finite and >= 0; throws
// std::invalid_argument otherwise or when it is empty.
std::vector<Merge> cluster(const std::vector<std::vector<double>>& distance, Linkage linkage);

// Labels 0 .. k-1 for the n leaves when the tree is cut into k clusters (undoing the last k - 1
// merges); labels are numbered in order of each cluster's smallest leaf. 1 <= k <= n.
std::vector<int> cut_tree(const std::vector<Merge>& merges, std::size_t n, int k);

// The leaves left to right as a dendrogram draws them (each merge puts `a` before `b`).
std::vector<int> leaf_order(const std::vector<Merge>& merges, std::size_t n);

}  // namespace sandpaper::experiment
