// Ray / quad tests per second of Ullner's kernel (seed 000 section 2.2), single thread:
// the templated hardware formulation in float and double, the double adapter that fills a
// SurfaceHit, and the host preprocessing. Rays are aimed near the quads so about half hit.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "firmware/kernels/ullner_quad.hpp"

namespace rtsim {
namespace {

constexpr int kQuads = 1024;
constexpr int kRays = 1024;

struct Scene {
  std::vector<std::array<Vec3, 4>> quads;
  std::vector<Ray> rays;
};

const Scene& scene() {
  static const Scene s = [] {
    Scene sc;
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    // Jittered grid quads in the z = 0 plane, tilted a little, so rays hit about half of the
    // time; the tilt keeps every edge pair non-parallel (the quadratic branch, the longer one).
    while (static_cast<int>(sc.quads.size()) < kQuads) {
      const double cx = 4 * U(rng), cy = 4 * U(rng);
      std::array<Vec3, 4> q = {Vec3(cx - 0.5 + 0.2 * U(rng), cy - 0.5 + 0.2 * U(rng), 0),
                               Vec3(cx + 0.5 + 0.2 * U(rng), cy - 0.5 + 0.2 * U(rng), 0),
                               Vec3(cx + 0.5 + 0.2 * U(rng), cy + 0.5 + 0.2 * U(rng), 0),
                               Vec3(cx - 0.5 + 0.2 * U(rng), cy + 0.5 + 0.2 * U(rng), 0)};
      for (Vec3& p : q) p.z = 0.3 * p.x - 0.2 * p.y;
      if (kernels::UllnerQuadParams<double>::precompute(q[0], q[1], q[2], q[3])) {
        sc.quads.push_back(q);
      }
    }
    for (int i = 0; i < kRays; ++i) {
      const auto& q = sc.quads[static_cast<std::size_t>(i)];
      const Vec3 c = 0.25 * (q[0] + q[1] + q[2] + q[3]);
      const Vec3 target = c + Vec3(0.7 * U(rng), 0.7 * U(rng), 0);
      const Vec3 o = c + Vec3(2 * U(rng), 2 * U(rng), 5.0);
      sc.rays.push_back(Ray{o, glm::normalize(target - o)});
    }
    return sc;
  }();
  return s;
}

// Ray i against quad i (the quad it was aimed near): the pipeline's steady state, one test per
// item.
template <typename T>
void BM_UllnerQuadIntersect(benchmark::State& state) {
  const Scene& sc = scene();
  std::vector<kernels::UllnerQuadParams<T>> params;
  std::vector<kernels::UllnerRay<T>> rays;
  for (const auto& q : sc.quads) {
    params.push_back(*kernels::UllnerQuadParams<T>::precompute(q[0], q[1], q[2], q[3]));
  }
  for (const Ray& r : sc.rays) {
    rays.push_back(kernels::UllnerRay<T>::make(Vec3T<T>(r.origin), Vec3T<T>(r.direction)));
  }
  std::size_t i = 0;
  long hits = 0;
  for (auto _ : state) {
    const auto res = kernels::intersect<T>(params[i], rays[i]);
    hits += res.hit();
    benchmark::DoNotOptimize(res);
    i = (i + 1) % params.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
}
BENCHMARK(BM_UllnerQuadIntersect<float>);
BENCHMARK(BM_UllnerQuadIntersect<double>);

// The adapter: per-ray setup, double kernel, SurfaceHit with the Phong-interpolated normal.
void BM_UllnerQuadKernelAdapter(benchmark::State& state) {
  const Scene& sc = scene();
  std::vector<kernels::UllnerQuadKernel> ks;
  const Vec3 n[4] = {Vec3(0, 0, 1), Vec3(0.1, 0, 1), Vec3(0.1, 0.1, 1), Vec3(0, 0.1, 1)};
  for (const auto& q : sc.quads) {
    ks.push_back(*kernels::UllnerQuadKernel::from(q[0], q[1], q[2], q[3], n));
  }
  std::size_t i = 0;
  long hits = 0;
  for (auto _ : state) {
    SurfaceHit h;
    hits += ks[i].intersect(sc.rays[i], 1e-9, kInfinity, h);
    benchmark::DoNotOptimize(h);
    i = (i + 1) % ks.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
}
BENCHMARK(BM_UllnerQuadKernelAdapter);

// Host preprocessing: four vertices -> twenty parameters.
template <typename T>
void BM_UllnerQuadPrecompute(benchmark::State& state) {
  const Scene& sc = scene();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& q = sc.quads[i];
    auto p = kernels::UllnerQuadParams<T>::precompute_checked(q[0], q[1], q[2], q[3]);
    benchmark::DoNotOptimize(p);
    i = (i + 1) % sc.quads.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_UllnerQuadPrecompute<float>);
BENCHMARK(BM_UllnerQuadPrecompute<double>);

}  // namespace
}  // namespace rtsim
