#include "platform/functional/functional_renderer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>

#include "firmware/shading/camera.hpp"
#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/shading/whitted_shader.hpp"
#include "firmware/tasks/ray_tree.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
#include "platform/functional/every_core.hpp"
#include "platform/functional/frame_state.hpp"

namespace rtsim::functional {

using shading::TracedRay;

namespace {

/// Traces the rows of `frame` (those flagged in `rows`, or all) with up to `threads` threads;
/// returns the threads that ran. Rows are handed out dynamically; a pixel is only ever touched
/// by the thread of its row, so the image does not depend on the thread count.
int trace_rows(const scenes::Scene& scene, const Tracer& tracer, const shading::ShadeParams& shade,
               FrameState& frame, const std::vector<char>* rows, int threads,
               const std::function<void(int, int)>& progress) {
  const int w = frame.width(), h = frame.height(), spp = frame.spp();
  shading::PinholeCamera camera(scene.camera, w, h);
  const int thread_count = std::max(1, threads);
  std::atomic<int> next_row{0};
  std::atomic<int> rows_done{0};
  std::vector<TraceCounters> per_thread(static_cast<std::size_t>(thread_count));

  auto worker = [&](int t) {
    TraceCounters& counters = per_thread[static_cast<std::size_t>(t)];
    std::vector<TracedRay> stack, spawned;
    tasks::ShadeTask task(scene, shade);
    for (int y = next_row.fetch_add(1); y < h; y = next_row.fetch_add(1)) {
      if (rows && !(*rows)[static_cast<std::size_t>(y)]) continue;
      tasks::VisionRayTask vision(camera, w, h, spp, static_cast<std::uint32_t>(y * w),
                                  static_cast<std::uint32_t>((y + 1) * w));
      while (!vision.done()) {
        int sample = 0;
        const TracedRay r = vision.next(sample);
        bool first = true;
        tasks::trace_ray_tree(r, tracer, task, frame.fb(), counters, stack, spawned,
                              [&](const TracedRay& ray, bool found, const Hit& hit) {
                                if (first && sample == 0)
                                  frame.record_primary(ray.pixel, found, hit);
                                first = false;
                              });
      }
      const int done = rows_done.fetch_add(1) + 1;
      if (t == 0 && progress) progress(done, h);
    }
  };

  const int ran = run_on_threads(thread_count, worker);
  for (const auto& c : per_thread) frame.counters() += c;
  return ran;
}

}  // namespace

RenderResult render(const scenes::Scene& scene, const Tracer& tracer, const RenderOptions& opts) {
  const auto start = std::chrono::steady_clock::now();
  const int w = opts.width > 0 ? opts.width : scene.camera.width;
  const int h = opts.height > 0 ? opts.height : scene.camera.height;
  const int spp = std::max(1, opts.spp);
  FrameState frame(w, h, spp, opts.aov_id, opts.aov_depth);
  const int threads =
      trace_rows(scene, tracer, opts.shade, frame, nullptr, opts.threads, opts.progress);
  if (opts.progress) opts.progress(h, h);
  RenderResult result =
      frame.finish(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  result.threads = threads;
  return result;
}

void render_rows(const scenes::Scene& scene, const Tracer& tracer,
                 const shading::ShadeParams& shade, FrameState& frame,
                 const std::vector<char>& rows) {
  // The machine's simulation is over: every core may trace.
  (void)trace_rows(scene, tracer, shade, frame, &rows, every_core(), {});
}

}  // namespace rtsim::functional
