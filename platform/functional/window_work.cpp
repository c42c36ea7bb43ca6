#include "platform/functional/window_work.hpp"

#include <algorithm>
#include <atomic>
#include <numeric>

#include "firmware/shading/camera.hpp"
#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/tasks/ray_tree.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
#include "platform/functional/every_core.hpp"

namespace rtsim::functional {

namespace {
/// The first column of row `y`'s subsample: it moves from row to row through every residue of
/// the stride (by the multiplier nearest stride / golden ratio that is prime to it), so that no
/// column of the image is always left out and the rows' errors do not add up alike (a fixed set
/// of columns would miss an object's edge in every row).
int column_offset(int y, int stride) {
  if (stride <= 1) return 0;
  int q = std::max(1, static_cast<int>(stride * 0.618));
  while (std::gcd(q, stride) != 1) --q;
  return static_cast<int>((static_cast<long>(y) * q + stride / 2) % stride);
}
}  // namespace

std::vector<WindowWork> window_work(const scenes::Scene& scene, const Tracer& tracer,
                                    const shading::ShadeParams& shade, int width, int height,
                                    int spp, int window_rows, int stride,
                                    const std::vector<char>& whole_rows) {
  const int rows_per = std::max(1, window_rows), step = std::max(1, stride);
  const int windows = (height + rows_per - 1) / rows_per;
  shading::PinholeCamera camera(scene.camera, width, height);
  // Counted by row, so that the threads' shares do not matter; summed into windows after.
  std::vector<TraceCounters> by_row(static_cast<std::size_t>(height)),
      sub_by_row(static_cast<std::size_t>(height));
  auto whole = [&](int y) {
    return static_cast<std::size_t>(y) < whole_rows.size() &&
           whole_rows[static_cast<std::size_t>(y)];
  };
  // The contributions land in a scratch buffer, never the run's.
  shading::PixelAccumulator scratch(width, height);
  // Rows of one pass (the whole ones, then the others' subsamples), on every core: the
  // machine's simulation is over.
  auto pass = [&](bool whole_pass) {
    std::atomic<int> next_row{0};
    run_on_threads(every_core(), [&](int) {
      std::vector<shading::TracedRay> stack, spawned;
      tasks::ShadeTask task(scene, shade);
      for (int y = next_row.fetch_add(1); y < height; y = next_row.fetch_add(1)) {
        if (whole(y) != whole_pass) continue;
        const int first = std::min(column_offset(y, step), width - 1);
        for (int x = whole_pass ? 0 : first; x < width; x += whole_pass ? 1 : step) {
          const bool in_sub = x >= first && (x - first) % step == 0;
          TraceCounters& counters = (in_sub ? sub_by_row : by_row)[static_cast<std::size_t>(y)];
          const auto pixel = static_cast<std::uint32_t>(y * width + x);
          tasks::VisionRayTask vision(camera, width, height, spp, pixel, pixel + 1);
          while (!vision.done()) {
            int sample = 0;
            const shading::TracedRay r = vision.next(sample);
            tasks::trace_ray_tree(r, tracer, task, scratch, counters, stack, spawned,
                                  [](const shading::TracedRay&, bool, const Hit&) {});
          }
        }
      }
    });
  };
  // The rows' counts summed into their windows.
  auto by_window = [&] {
    std::vector<WindowWork> out(static_cast<std::size_t>(windows));
    for (int y = 0; y < height; ++y) {
      const TraceCounters& sub = sub_by_row[static_cast<std::size_t>(y)];
      const TraceCounters& rest = by_row[static_cast<std::size_t>(y)];
      WindowWork& w = out[static_cast<std::size_t>(y / rows_per)];
      const double sub_tests = static_cast<double>(sub.intersection_tests + sub.box_tests);
      const double sub_rays = static_cast<double>(sub.total_rays());
      w.sub_tests += sub_tests;
      w.sub_rays += sub_rays;
      if (whole(y)) {
        // A window is whole when its rows are (the detailed windows' rows are all flagged).
        w.whole = true;
        w.tests += sub_tests + static_cast<double>(rest.intersection_tests + rest.box_tests);
        w.rays += sub_rays + static_cast<double>(rest.total_rays());
      }
    }
    return out;
  };
  pass(true);
  std::vector<WindowWork> out = by_window();
  // Windows in detail that all did the same work (a brute-force search on rays that spawn
  // nothing) leave the regression nothing to fit: the estimate is the systematic one, and the
  // other rows' subsample would be traced for nothing.
  const WindowWork* alike = nullptr;
  for (const WindowWork& w : out) {
    if (!w.whole) continue;
    if (!alike) {
      alike = &w;
    } else if (w.tests != alike->tests || w.rays != alike->rays) {
      pass(false);
      return by_window();
    }
  }
  return out;
}

}  // namespace rtsim::functional
