#include "platform/functional/functional_renderer.hpp"

#include <chrono>
#include <cmath>
#include <thread>

#include "firmware/shading/camera.hpp"
#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/shading/whitted_shader.hpp"

namespace rtsim::functional {
namespace {

using shading::ShadeOutput;
using shading::TracedRay;

/// Trace one ray tree depth-first. Contributions go into `fb` (order-independent).
void trace_tree(const TracedRay& primary, const scenes::Scene& scene, const Tracer& tracer,
                const shading::ShadeParams& params, shading::PixelAccumulator& fb,
                TraceCounters& counters, std::vector<TracedRay>& stack, ShadeOutput& scratch,
                Hit* primary_hit) {
  stack.clear();
  stack.push_back(primary);
  bool first = true;
  while (!stack.empty()) {
    const TracedRay r = stack.back();
    stack.pop_back();
    counters.count_ray(r.kind);
    if (r.kind == RayKind::Shadow) {
      if (!tracer.any_hit(r.ray, 0.0, r.t_max, counters))
        fb.add(r.pixel, shading::miss_contribution(r, scene.background));
      continue;
    }
    Hit hit;
    const double t_min = r.kind == RayKind::Primary ? scene.camera.hither : 0.0;
    const bool found = tracer.closest_hit(r.ray, t_min, kInfinity, hit, counters);
    if (first && primary_hit) *primary_hit = found ? hit : Hit{};
    first = false;
    if (!found) {
      fb.add(r.pixel, shading::miss_contribution(r, scene.background));
      continue;
    }
    counters.cost += shading::shade_hit(r, hit, scene.materials[hit.material], scene.lights,
                                        params, scratch);
    fb.add(r.pixel, scratch.local);
    // Push in reverse so rays are traced in the order they were spawned.
    for (auto it = scratch.spawned.rbegin(); it != scratch.spawned.rend(); ++it)
      stack.push_back(*it);
  }
}

}  // namespace

void sample_offset(int s, double& dx, double& dy) {
  // R2 sequence (generalised golden ratio in 2-D): alpha = (1/g, 1/g^2), g^3 = g + 1.
  constexpr double a1 = 0.7548776662466927;
  constexpr double a2 = 0.5698402909980532;
  dx = std::fmod(0.5 + a1 * s, 1.0);
  dy = std::fmod(0.5 + a2 * s, 1.0);
}

RenderResult render(const scenes::Scene& scene, const Tracer& tracer, const RenderOptions& opts) {
  const auto start = std::chrono::steady_clock::now();
  RenderResult res;
  res.width = opts.width > 0 ? opts.width : scene.camera.width;
  res.height = opts.height > 0 ? opts.height : scene.camera.height;
  const int w = res.width;
  const int h = res.height;
  const int spp = std::max(1, opts.spp);
  const std::size_t n = static_cast<std::size_t>(w) * h;
  shading::PinholeCamera camera(scene.camera, w, h);
  shading::PixelAccumulator fb(w, h);
  if (opts.aov_id) res.id.assign(n, -1.0f);
  if (opts.aov_depth) res.depth.assign(n, std::numeric_limits<float>::infinity());

  const int thread_count = std::max(1, opts.threads);
  std::atomic<int> next_row{0};
  std::atomic<int> rows_done{0};
  std::vector<TraceCounters> per_thread(static_cast<std::size_t>(thread_count));

  auto worker = [&](int t) {
    TraceCounters& counters = per_thread[static_cast<std::size_t>(t)];
    std::vector<TracedRay> stack;
    ShadeOutput scratch;
    for (int y = next_row.fetch_add(1); y < h; y = next_row.fetch_add(1)) {
      for (int x = 0; x < w; ++x) {
        const auto pixel = static_cast<std::uint32_t>(y * w + x);
        for (int s = 0; s < spp; ++s) {
          double dx = 0.5, dy = 0.5;
          sample_offset(s, dx, dy);
          TracedRay r;
          r.ray = camera.primary(x + dx, y + dy);
          r.pixel = pixel;
          Hit primary_hit;
          trace_tree(r, scene, tracer, opts.shade, fb, counters, stack, scratch,
                     s == 0 ? &primary_hit : nullptr);
          if (s == 0 && primary_hit.valid()) {
            if (opts.aov_id) res.id[pixel] = static_cast<float>(primary_hit.prim_id);
            if (opts.aov_depth) res.depth[pixel] = static_cast<float>(primary_hit.surface.t);
          }
        }
      }
      const int done = rows_done.fetch_add(1) + 1;
      if (t == 0 && opts.progress) opts.progress(done, h);
    }
  };

  std::vector<std::thread> pool;
  for (int t = 1; t < thread_count; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (auto& th : pool) th.join();
  if (opts.progress) opts.progress(h, h);

  for (const auto& c : per_thread) res.counters += c;
  res.rgb.resize(n * 3);
  for (std::size_t i = 0; i < n; ++i) {
    const Color c = fb.value(static_cast<std::uint32_t>(i), spp);
    res.rgb[3 * i + 0] = static_cast<float>(c.r);
    res.rgb[3 * i + 1] = static_cast<float>(c.g);
    res.rgb[3 * i + 2] = static_cast<float>(c.b);
  }
  res.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return res;
}

}  // namespace rtsim::functional
