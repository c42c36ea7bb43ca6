// Ray/Bezier-patch intersections per second, single thread: Wang, Lewis & Hung's pipeline in
// float and double (10 loop stages, the hardware's count, seed 002 L284) and the double
// reference solver. The jobs are the (ray, patch) pairs an acceleration structure would hand
// over: camera rays at the Newell teapot, each with every patch whose control-point box it
// meets (a mix of hits and misses, like the real workload). The paper's estimate for its
// 600-DSP pipeline is 9.16e5 jobs/s (Table 4, L437).
#include <benchmark/benchmark.h>

#include <vector>

#include "firmware/kernels/bezier_patch_kernel.hpp"
#include "firmware/kernels/bezier_reference.hpp"
#include "firmware/kernels/bezier_wang.hpp"
#include "tests/bezier_teapot.hpp"

namespace {

using namespace rtsim;
using namespace rtsim::kernels;

struct Job {
  Ray ray;
  int patch;
};

struct Workload {
  std::vector<scenes::BezierPatch> patches;
  std::vector<ControlNet<double>> nets;
  std::vector<ControlNet<float>> nets_f;
  std::vector<BezierPatchKernel> kernels;
  std::vector<Job> jobs;
  double hit_fraction = 0;

  Workload() {
    patches = bezier_test::teapot();
    Bounds box;
    for (const auto& p : patches) {
      nets.push_back(control_net_from(p));
      nets_f.push_back(convert_net<float>(nets.back()));
      kernels.push_back(BezierPatchKernel::from(p));
      box.extend(kernels.back().bounds());
    }
    const bezier_test::FramingCamera cam(box, Vec3(-0.55, -1.0, 0.6), 64, 2.0, 1.5);
    int hits = 0;
    for (int j = 0; j < cam.n; ++j)
      for (int i = 0; i < cam.n; ++i) {
        const Ray r = cam.ray(i, j);
        for (int p = 0; p < static_cast<int>(patches.size()); ++p) {
          double t0, t1;
          if (!kernels[static_cast<std::size_t>(p)].bounds().intersect(r, 0.0, kInfinity, t0, t1))
            continue;
          jobs.push_back({r, p});
          SurfaceHit h;
          hits += reference_intersect(nets[static_cast<std::size_t>(p)], r, 0.0, kInfinity, h);
        }
      }
    hit_fraction = static_cast<double>(hits) / static_cast<double>(jobs.size());
  }
};

const Workload& workload() {
  static const Workload w;
  return w;
}

template <typename T>
void BM_Wang(benchmark::State& state) {
  const Workload& w = workload();
  const int iterations = static_cast<int>(state.range(0));
  std::size_t k = 0;
  WangCounters counters;
  for (auto _ : state) {
    const Job& job = w.jobs[k];
    k = k + 1 == w.jobs.size() ? 0 : k + 1;
    const auto& net = [&]() -> const ControlNet<T>& {
      if constexpr (std::is_same_v<T, float>)
        return w.nets_f[static_cast<std::size_t>(job.patch)];
      else
        return w.nets[static_cast<std::size_t>(job.patch)];
    }();
    auto r = wang_intersect<T>(net, Vec3T<T>(job.ray.origin), Vec3T<T>(job.ray.direction),
                               iterations, &counters);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hit_fraction"] = w.hit_fraction;
  state.counters["hull_tests/job"] = static_cast<double>(counters.hull_tests) / counters.calls;
  state.counters["fp_ops/job"] = static_cast<double>(wang_cost(counters).fp_ops()) / counters.calls;
}
BENCHMARK(BM_Wang<float>)->Arg(10)->Arg(6);
BENCHMARK(BM_Wang<double>)->Arg(10)->Arg(6);

// The adapter: Wang in float plus the double normal from the original patch.
void BM_BezierPatchKernel(benchmark::State& state) {
  const Workload& w = workload();
  std::size_t k = 0;
  for (auto _ : state) {
    const Job& job = w.jobs[k];
    k = k + 1 == w.jobs.size() ? 0 : k + 1;
    SurfaceHit h;
    benchmark::DoNotOptimize(
        w.kernels[static_cast<std::size_t>(job.patch)].intersect(job.ray, 0.0, kInfinity, h));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BezierPatchKernel);

void BM_Reference(benchmark::State& state) {
  const Workload& w = workload();
  std::size_t k = 0;
  ReferenceCounters counters;
  for (auto _ : state) {
    const Job& job = w.jobs[k];
    k = k + 1 == w.jobs.size() ? 0 : k + 1;
    SurfaceHit h;
    benchmark::DoNotOptimize(reference_intersect(w.nets[static_cast<std::size_t>(job.patch)],
                                                 job.ray, 0.0, kInfinity, h, &counters));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["box_tests/job"] = static_cast<double>(counters.box_tests) / counters.calls;
  state.counters["newton_it/job"] =
      static_cast<double>(counters.newton_iterations) / counters.calls;
}
BENCHMARK(BM_Reference);

}  // namespace
