#pragma once
// The work of each window of a sampled simulation, counted by the functional twin: the
// auxiliary variable of the work-weighted estimate (platform/machines/frame_sample.hpp). A
// sampled run must know how much work lies in the windows it does not simulate; tracing them
// whole would cost the functional render the run is meant to avoid, so of those only every
// `stride`-th pixel of each row is traced (the first column moving from row to row), with the
// machine's own tracer and shading, into a scratch frame buffer.
// The windows simulated in detail (a K-th of the frame) are traced whole, and their subsample
// counted on the way: the estimate regresses their time on their exact work, and calibrates the
// subsample against it (two-phase sampling).
#include <cstdint>
#include <vector>

#include "firmware/scene.hpp"
#include "firmware/shading/shade_params.hpp"
#include "firmware/trace_counters.hpp"
#include "firmware/tracer.hpp"

namespace rtsim::functional {

/// The work of one window, as the twin's counters count it: intersection tests (primitive and
/// bounding box) and rays (of every kind).
struct WindowWork {
  bool whole = false;    ///< every pixel traced: `tests` and `rays` are the window's own
  double tests = 0;      ///< whole: the window's; else 0
  double rays = 0;       ///< whole: the window's; else 0
  double sub_tests = 0;  ///< those of its subsample of columns
  double sub_rays = 0;
};

/// The work of each window of `window_rows` rows in a `width` x `height` frame of `spp` samples
/// a pixel: the rows flagged in `whole_rows` (one flag a row) traced whole, every `stride`-th
/// pixel of the others, on every core. Where the whole windows all did the same work, the
/// others are not traced (their subsample counts stay 0): there is nothing to regress on.
std::vector<WindowWork> window_work(const scenes::Scene& scene, const Tracer& tracer,
                                    const shading::ShadeParams& shade, int width, int height,
                                    int spp, int window_rows, int stride,
                                    const std::vector<char>& whole_rows);

}  // namespace rtsim::functional
