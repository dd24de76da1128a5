// Cost of one ProxyRenderer::update_rt on a sphere of about 1k, 10k and 100k triangles (it must grow
// at most logarithmically with the triangle count; docs/performance.md): the device moves on a circle of
// 5 mm radius pressed 1 mm into the surface, a turn every 1000 ticks (31 um a tick, 31 mm/s at
// 1 kHz). BM_ProxyUpdate reports the mean; BM_ProxyUpdatePercentiles times each tick on its own
// (steady_clock, ~20 ns of its own per reading) and reports p50 and p99 as counters.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

namespace sandpaper::shapes {
namespace {

constexpr double kRadius = 0.05;

struct Scene {
  Mesh mesh;
  Bvh bvh;
  std::vector<glm::dvec3> path;  // one turn of the device, 1000 ticks
};

// Sphere resolutions giving 1,024, 10,000 and 99,840 triangles (2 n_lon (n_lat - 1)).
const Scene& scene(std::int64_t triangles) {
  static std::unique_ptr<Scene> scenes[3];
  const int i = triangles <= 1024 ? 0 : (triangles <= 10000 ? 1 : 2);
  if (!scenes[i]) {
    const std::uint32_t n_lon[] = {32, 100, 320}, n_lat[] = {17, 51, 157};
    Mesh mesh = uv_sphere(kRadius, n_lon[i], n_lat[i]);
    Bvh bvh = Bvh::build_nonrt(mesh);
    scenes[i] = std::make_unique<Scene>(Scene{std::move(mesh), std::move(bvh), {}});
    const glm::dvec3 centre = glm::normalize(glm::dvec3{0.3, 0.5, 0.8});
    const glm::dvec3 u = glm::normalize(glm::cross(centre, glm::dvec3{0, 0, 1}));
    const glm::dvec3 v = glm::cross(centre, u);
    for (int k = 0; k < 1000; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 1000.0;
      const glm::dvec3 on_surface = glm::normalize(centre * kRadius + 0.005 * (std::cos(a) * u + std::sin(a) * v));
      scenes[i]->path.push_back(on_surface * (kRadius - 0.001));
    }
  }
  return *scenes[i];
}

SurfaceMaterial material(bool friction) {
  return friction ? SurfaceMaterial{500.0, 0.0, 0.4, 0.3} : SurfaceMaterial{500.0};
}

void BM_ProxyUpdate(benchmark::State& state) {
  const Scene& s = scene(state.range(0));
  ProxyRenderer renderer(s.mesh, s.bvh, {material(state.range(1) != 0)});
  renderer.reset_rt(s.path[0] * (kRadius + 0.002) / (kRadius - 0.001));
  for (int k = 0; k < 2000; ++k) renderer.update_rt(s.path[static_cast<std::size_t>(k) % s.path.size()]);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(renderer.update_rt(s.path[k]));
    k = k + 1 == s.path.size() ? 0 : k + 1;
  }
  state.counters["triangles"] = static_cast<double>(s.mesh.triangle_count());
  state.counters["in_contact"] = renderer.contact_rt().in_contact ? 1 : 0;
}
BENCHMARK(BM_ProxyUpdate)->ArgNames({"triangles", "friction"})->ArgsProduct({{1024, 10000, 99840}, {0, 1}});

void BM_ProxyUpdatePercentiles(benchmark::State& state) {
  const Scene& s = scene(state.range(0));
  ProxyRenderer renderer(s.mesh, s.bvh, {material(state.range(1) != 0)});
  renderer.reset_rt(s.path[0] * (kRadius + 0.002) / (kRadius - 0.001));
  for (int k = 0; k < 2000; ++k) renderer.update_rt(s.path[static_cast<std::size_t>(k) % s.path.size()]);
  std::vector<double> ns;
  ns.reserve(1 << 20);
  std::size_t k = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(renderer.update_rt(s.path[k]));
    const auto t1 = std::chrono::steady_clock::now();
    if (ns.size() < ns.capacity()) ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    k = k + 1 == s.path.size() ? 0 : k + 1;
  }
  std::sort(ns.begin(), ns.end());
  auto at = [&](double q) { return ns.empty() ? 0.0 : ns[static_cast<std::size_t>(q * static_cast<double>(ns.size() - 1))]; };
  state.counters["p50_ns"] = at(0.50);
  state.counters["p99_ns"] = at(0.99);
  state.counters["triangles"] = static_cast<double>(s.mesh.triangle_count());
}
BENCHMARK(BM_ProxyUpdatePercentiles)->ArgNames({"triangles", "friction"})->ArgsProduct({{1024, 10000, 99840}, {0, 1}});

}  // namespace
}  // namespace sandpaper::shapes

BENCHMARK_MAIN();
