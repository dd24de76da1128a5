#include "sandpaper/experiment/clustering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sandpaper::experiment {

std::vector<Merge> cluster(const std::vector<std::vector<double>>& distance, Linkage linkage) {
  const std::size_t n = distance.size();
  if (n == 0) throw std::invalid_argument("cluster: empty distance matrix");
  for (std::size_t i = 0; i < n; ++i) {
    if (distance[i].size() != n) throw std::invalid_argument("cluster: distance matrix is not square");
    for (std::size_t j = 0; j < n; ++j) {
      const double v = distance[i][j];
      if (!std::isfinite(v) || v < 0 || v != distance[j][i])
        throw std::invalid_argument("cluster: distances must be finite, >= 0 and symmetric");
    }
  }
  // Naive O(n^3): stimulus sets are tens of items. d holds cluster-to-cluster distances.
  std::vector<std::vector<double>> d = distance;
  std::vector<int> id(n), size(n, 1);
  std::vector<bool> alive(n, true);
  for (std::size_t i = 0; i < n; ++i) id[i] = static_cast<int>(i);
  std::vector<Merge> merges;
  for (std::size_t step = 0; step + 1 < n; ++step) {
    std::size_t bi = 0, bj = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      if (!alive[i]) continue;
      for (std::size_t j = i + 1; j < n; ++j)
        if (alive[j] && d[i][j] < best) {
          best = d[i][j];
          bi = i;
          bj = j;
        }
    }
    merges.push_back({std::min(id[bi], id[bj]), std::max(id[bi], id[bj]), best, size[bi] + size[bj]});
    for (std::size_t k = 0; k < n; ++k) {
      if (!alive[k] || k == bi || k == bj) continue;
      const double v = linkage == Linkage::Single
                           ? std::min(d[bi][k], d[bj][k])
                           : (d[bi][k] * size[bi] + d[bj][k] * size[bj]) / static_cast<double>(size[bi] + size[bj]);
      d[bi][k] = d[k][bi] = v;
    }
    alive[bj] = false;
    size[bi] += size[bj];
    id[bi] = static_cast<int>(n + step);
  }
  return merges;
}

std::vector<int> cut_tree(const std::vector<Merge>& merges, std::size_t n, int k) {
  if (k < 1 || static_cast<std::size_t>(k) > n) throw std::invalid_argument("cut_tree: k must be in 1..n");
  // Union the leaves through the first n - k merges.
  std::vector<int> parent(2 * n);
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)];
    return x;
  };
  for (std::size_t m = 0; m + static_cast<std::size_t>(k) < n; ++m) {
    const int c = static_cast<int>(n + m);
    parent[static_cast<std::size_t>(find(merges[m].a))] = c;
    parent[static_cast<std::size_t>(find(merges[m].b))] = c;
  }
  std::vector<int> labels(n, -1), root_label(2 * n, -1);
  int next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(find(static_cast<int>(i)));
    if (root_label[r] < 0) root_label[r] = next++;
    labels[i] = root_label[r];
  }
  return labels;
}

std::vector<int> leaf_order(const std::vector<Merge>& merges, std::size_t n) {
  if (n == 1) return {0};
  std::vector<int> out;
  std::vector<int> stack{static_cast<int>(n + merges.size() - 1)};
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    if (c < static_cast<int>(n)) {
      out.push_back(c);
      continue;
    }
    const auto& m = merges[static_cast<std::size_t>(c) - n];
    stack.push_back(m.b);
    stack.push_back(m.a);
  }
  return out;
}

}  // namespace sandpaper::experiment
