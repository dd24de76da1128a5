// Cost of one ProxyRenderer::update_rt on a sphere of about 1k, 10k and 100k triangles (it must grow
// at most logarithmically with the triangle count; docs/performance.md): the device moves on a circle of
// 5 mm radius pressed 1 mm into the surface, a turn every 1000 ticks (31 um a tick, 31 mm/s at
// 1 kHz). BM_ProxyUpdate reports the mean; BM_ProxyUpdatePercentiles times each tick on its own
// (time_each: the time-stamp counter, fenced) and reports p50 and p99 as counters.
// BM_TexturedSphere is the whole 3-D contact tick of a scene (TexturedContact: the proxy plus a
// 2.5 mm grating laid through the sphere's UVs): what one servo tick of a textured scene costs.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"
#include "sandpaper/shapes/textured_contact.hpp"

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


// A sine grating of 2.5 mm period and 0.5 N force amplitude (the thesis' gratings, 3.5), as the
// compiler writes one: one period of force samples.
schema::PatchProgram grating_program() {
  schema::PatchProgram p;
  schema::GratingTerm g;
  g.period_m = 0.0025;
  for (int i = 0; i < 64; ++i) g.force_N.push_back(static_cast<float>(-0.5 * std::sin(2.0 * std::numbers::pi * i / 64.0)));
  p.terms.emplace_back(std::move(g));
  p.max_lateral_force_N = 0.5;
  return p;
}

// The textured sphere's contact: the proxy plus the grating laid once round the equator.
TexturedContact textured(const Scene& s, bool friction) {
  std::vector<std::optional<SurfaceTexture>> textures;
  textures.emplace_back(SurfaceTexture::for_program_nonrt(
      grating_program(), glm::dvec2{2.0 * std::numbers::pi * kRadius, std::numbers::pi * kRadius}));
  return TexturedContact(s.mesh, s.bvh, {material(friction)}, std::move(textures));
}

// Puts the contact on the circle and runs two turns, so that what is timed is steady sliding.
template <class Contact>
void settle(Contact& contact, const Scene& s) {
  contact.reset_rt(s.path[0] * (kRadius + 0.002) / (kRadius - 0.001));
  for (int k = 0; k < 2000; ++k) contact.update_rt(s.path[static_cast<std::size_t>(k) % s.path.size()]);
}

// Mean cost of an update over the benchmark's iterations.
template <class Contact>
void time_updates(benchmark::State& state, Contact& contact, const Scene& s) {
  settle(contact, s);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(contact.update_rt(s.path[k]));
    k = k + 1 == s.path.size() ? 0 : k + 1;
  }
  state.counters["triangles"] = static_cast<double>(s.mesh.triangle_count());
}

// A timestamp for timing one update: x86's time-stamp counter, fenced so that the update's work
// stays between two readings (a pair costs ~10 ns here, against ~48 ns for two steady_clock
// readings on this VM; the counter is invariant, /proc/cpuinfo's constant_tsc and nonstop_tsc);
// elsewhere steady_clock in ns.
inline std::uint64_t stamp() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  _mm_lfence();
  const std::uint64_t t = __rdtsc();
  _mm_lfence();
  return t;
#else
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::steady_clock::now().time_since_epoch())
                                        .count());
#endif
}

// Times each call of `work` on its own, stamps converted to ns by steady_clock over the whole loop:
// p50_ns, p99_ns and clock_pair_ns (the median of two stamps with nothing between, in every
// figure: the tick's own cost is about p50 - clock_pair).
template <class Work>
void time_each(benchmark::State& state, Work work) {
  std::vector<std::uint64_t> ticks, empty;
  ticks.reserve(1 << 20);
  empty.reserve(1 << 16);
  const auto c0 = std::chrono::steady_clock::now();
  const std::uint64_t s0 = stamp();
  for (auto _ : state) {
    const std::uint64_t t0 = stamp();
    work();
    const std::uint64_t t1 = stamp();
    if (ticks.size() < ticks.capacity()) ticks.push_back(t1 - t0);
    if (empty.size() < empty.capacity() && (ticks.size() & 15) == 0) {
      const std::uint64_t e0 = stamp();
      const std::uint64_t e1 = stamp();
      empty.push_back(e1 - e0);
    }
  }
  const std::uint64_t s1 = stamp();
  const double ns_per_stamp =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - c0).count() / static_cast<double>(s1 - s0);
  auto at = [&](std::vector<std::uint64_t>& v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return ns_per_stamp * static_cast<double>(v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))]);
  };
  state.counters["p50_ns"] = at(ticks, 0.50);
  state.counters["p99_ns"] = at(ticks, 0.99);
  state.counters["clock_pair_ns"] = at(empty, 0.50);
}

// Each update timed on its own (time_each).
template <class Contact>
void time_each_update(benchmark::State& state, Contact& contact, const Scene& s) {
  settle(contact, s);
  std::size_t k = 0;
  time_each(state, [&] {
    benchmark::DoNotOptimize(contact.update_rt(s.path[k]));
    k = k + 1 == s.path.size() ? 0 : k + 1;
  });
  state.counters["triangles"] = static_cast<double>(s.mesh.triangle_count());
}

void BM_ProxyUpdate(benchmark::State& state) {
  const Scene& s = scene(state.range(0));
  ProxyRenderer renderer(s.mesh, s.bvh, {material(state.range(1) != 0)});
  time_updates(state, renderer, s);
  state.counters["in_contact"] = renderer.contact_rt().in_contact ? 1 : 0;
  // How often the neighbourhood was gathered again, and how many triangles it last held.
  state.counters["ticks_per_gather"] = static_cast<double>(state.iterations() + 2000) /
                                       static_cast<double>(std::max<std::uint64_t>(1, renderer.nearby_rt().gathers()));
  state.counters["nearby_triangles"] = static_cast<double>(renderer.nearby_rt().size());
}
BENCHMARK(BM_ProxyUpdate)->ArgNames({"triangles", "friction"})->ArgsProduct({{1024, 10000, 99840}, {0, 1}});

void BM_ProxyUpdatePercentiles(benchmark::State& state) {
  const Scene& s = scene(state.range(0));
  ProxyRenderer renderer(s.mesh, s.bvh, {material(state.range(1) != 0)});
  time_each_update(state, renderer, s);
}
BENCHMARK(BM_ProxyUpdatePercentiles)->ArgNames({"triangles", "friction"})->ArgsProduct({{1024, 10000, 99840}, {0, 1}});

void BM_TexturedSphere(benchmark::State& state) {
  const Scene& s = scene(state.range(0));
  TexturedContact contact = textured(s, state.range(1) != 0);
  time_updates(state, contact, s);
  // Proof that the texture is felt on the path: its force at the last tick (N).
  state.counters["texture_N"] = glm::length(contact.texture_force_rt());
}
BENCHMARK(BM_TexturedSphere)->ArgNames({"triangles", "friction"})->ArgsProduct({{1024, 10000, 99840}, {0, 1}});

void BM_TexturedSpherePercentiles(benchmark::State& state) {
  const Scene& s = scene(state.range(0));
  TexturedContact contact = textured(s, state.range(1) != 0);
  time_each_update(state, contact, s);
}
BENCHMARK(BM_TexturedSpherePercentiles)->ArgNames({"triangles", "friction"})->ArgsProduct({{1024, 10000, 99840}, {0, 1}});

// What the timing adds to each timed update: an empty section timed as the updates are.
void BM_ClockPair(benchmark::State& state) {
  time_each(state, [] {});
}
BENCHMARK(BM_ClockPair);

}  // namespace
}  // namespace sandpaper::shapes

BENCHMARK_MAIN();
