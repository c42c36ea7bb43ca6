// Intersection tests per second for each kernel, single thread. Each benchmark tests 1024 rays
// against 64 primitives of one kind (rays aimed into the cluster; the hit rate is reported);
// items_per_second is tests per second.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "firmware/kernels/cone.hpp"
#include "firmware/kernels/sphere.hpp"
#include "firmware/kernels/triangle.hpp"

namespace {

using namespace rtsim;
using namespace rtsim::kernels;

constexpr int kRays = 1024;
constexpr int kPrims = 64;

struct Rng {
  std::mt19937_64 e{1234};
  double u(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(e); }
  Vec3 box(double h) { return {u(-h, h), u(-h, h), u(-h, h)}; }
};

std::vector<Ray> rays_towards(Rng& r, double spread) {
  std::vector<Ray> rays;
  for (int i = 0; i < kRays; ++i) {
    const Vec3 o = r.box(6), target = r.box(spread);
    rays.push_back(Ray{o, glm::normalize(target - o)});
  }
  return rays;
}

/// Every ray against every primitive; `RayT` is a Ray or a kernel's prepared ray.
template <typename Kernel, typename RayT>
void run(benchmark::State& state, const std::vector<Kernel>& prims, const std::vector<RayT>& rays) {
  std::int64_t hits = 0;
  for (auto _ : state) {
    for (const RayT& ray : rays) {
      for (const Kernel& k : prims) {
        SurfaceHit h;
        hits += k.intersect(ray, 1e-9, kInfinity, h);
        benchmark::DoNotOptimize(h);
      }
    }
  }
  state.SetItemsProcessed(state.iterations() * kRays * kPrims);
  state.counters["hit_rate"] =
      double(hits) / double(state.iterations() * std::int64_t(kRays) * kPrims);
}

template <typename T>
std::vector<TriangleKernelT<T>> triangles(Rng& r) {
  std::vector<TriangleKernelT<T>> v;
  while (v.size() < kPrims) {
    const Vec3 c = r.box(0.5);
    if (auto k = TriangleKernelT<T>::from(c + r.box(1), c + r.box(1), c + r.box(1), nullptr)) {
      v.push_back(*k);
    }
  }
  return v;
}

template <typename T>
void BM_Triangle(benchmark::State& state) {
  Rng r;
  const auto prims = triangles<T>(r);
  run(state, prims, rays_towards(r, 0.8));
}
BENCHMARK(BM_Triangle<double>);
BENCHMARK(BM_Triangle<float>);

// Ray setup (permutation and shear) done once per ray, as a machine would.
template <typename T>
void BM_TrianglePreparedRay(benchmark::State& state) {
  Rng r;
  const auto prims = triangles<T>(r);
  std::vector<ShearedRay<T>> rays;
  for (const Ray& ray : rays_towards(r, 0.8)) rays.push_back(ShearedRay<T>::make(ray));
  run(state, prims, rays);
}
BENCHMARK(BM_TrianglePreparedRay<double>);
BENCHMARK(BM_TrianglePreparedRay<float>);

void BM_Sphere(benchmark::State& state) {
  Rng r;
  std::vector<SphereKernel> prims;
  while (prims.size() < kPrims) prims.push_back(*SphereKernel::from({r.box(1), r.u(0.2, 1)}));
  run(state, prims, rays_towards(r, 1.2));
}
BENCHMARK(BM_Sphere);

void BM_Cone(benchmark::State& state) {
  const bool cylinder = state.range(0) != 0;
  Rng r;
  std::vector<ConeKernel> prims;
  while (prims.size() < kPrims) {
    scenes::Cone c;
    c.base = r.box(1);
    c.apex = c.base + r.box(1.5);
    c.base_radius = r.u(0.1, 0.8);
    c.apex_radius = cylinder ? c.base_radius : r.u(0.0, 0.8);
    if (auto k = ConeKernel::from(c)) prims.push_back(*k);
  }
  run(state, prims, rays_towards(r, 1.2));
}
BENCHMARK(BM_Cone)->Arg(0)->ArgName("cylinder");
BENCHMARK(BM_Cone)->Arg(1)->ArgName("cylinder");

}  // namespace
