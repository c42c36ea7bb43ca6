#pragma once
// The functional renderer: the firmware (camera, shading, kernels, acceleration) run with no
// timing at all. It is the golden image every machine must reproduce and the speed floor that
// machine wall times are reported against.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "firmware/scene.hpp"
#include "firmware/shading/shade_params.hpp"
#include "firmware/trace_counters.hpp"
#include "firmware/tracer.hpp"

namespace rtsim::functional {

struct RenderOptions {
  int width = 0;  ///< 0: the scene's resolution
  int height = 0;
  int spp = 1;  ///< samples per pixel
  int threads = 1;
  bool aov_id = false;
  bool aov_depth = false;
  shading::ShadeParams shade;
  /// Called after each row the calling thread finishes with (rows done, rows total).
  std::function<void(int, int)> progress;
};

struct RenderResult {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;    ///< width*height*3, linear
  std::vector<float> id;     ///< width*height, primitive index of the primary hit or -1
  std::vector<float> depth;  ///< width*height, primary hit distance or +inf
  TraceCounters counters;
  double wall_time_s = 0.0;
  /// Worker threads that ran: fewer than RenderOptions::threads when the system would not create
  /// more (the rows are shared out dynamically, so the image is the same).
  int threads = 1;
  /// A machine that draws lines (ullner-hidden-line) gives them as an SVG drawing too, which
  /// `render` and `run` write as drawing.svg; empty: no drawing.
  std::string drawing_svg{};
};

RenderResult render(const scenes::Scene& scene, const Tracer& tracer, const RenderOptions& opts);

class FrameState;

/// The flagged rows of `frame` (one flag per row), rendered as render() would, into its frame
/// buffer and AOVs, on every core: the rows a sampled simulation did not simulate in detail.
void render_rows(const scenes::Scene& scene, const Tracer& tracer,
                 const shading::ShadeParams& shade, FrameState& frame,
                 const std::vector<char>& rows);

}  // namespace rtsim::functional
