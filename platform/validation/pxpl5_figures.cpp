#include "platform/validation/pxpl5_figures.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "platform/validation/figure_registry.hpp"

namespace rtsim::validation {

namespace {

/// Fig. 9's system (L369): 21 GPs, 4 of them compositors, one master, 16 casters (the machine's
/// defaults), at 640 x 512 (eighty 64 x 64 squares, L360), on SPD's teapot; adaptive squares
/// from one ray per 16 x 16 to one per 4 x 4, rows a ray every 4 x 4. Two frames, the camera
/// turning a degree: the second is handed out in descending cost of the first.
RunRequest vol2_run(std::string key, const std::vector<std::string>& extra,
                    const std::string& scene = "builtin:spd-teapot") {
  std::vector<std::string> params = {"sampling.finest=4", "sampling.start=16", "frames=2",
                                     "camera.spin=1"};
  params.insert(params.end(), extra.begin(), extra.end());
  return machine_run_request(std::move(key), kPxpl5Machine, scene, 640, 512, params, 2e5);
}

/// X1's setups (chosen before measuring): the teapot at Fig. 9's full screen, three quarters of
/// the way and its own view, and three built-in scenes of other kinds at theirs (mirrors and
/// glass; Gaudet's sphere clusters; Ullner's cubes); the camera turns a degree.
struct OrderSetup {
  std::string label, scene;
  std::vector<std::string> params;
};
std::vector<OrderSetup> order_setups() {
  return {{"spd-teapot, camera.distance 0.5", "builtin:spd-teapot", {"camera.distance=0.5"}},
          {"spd-teapot, camera.distance 0.75", "builtin:spd-teapot", {"camera.distance=0.75"}},
          {"spd-teapot, its own view", "builtin:spd-teapot", {}},
          {"default", "builtin:default", {}},
          {"npp-412", "builtin:npp-412", {}},
          {"ullner-cubes", "builtin:ullner-cubes", {}}};
}

/// By-pass runs (L333-L350): builtin:default at 320 x 256.
RunRequest bypass_run(std::string key, const std::string& scene,
                      const std::vector<std::string>& params) {
  return machine_run_request(std::move(key), kPxpl5Machine, scene, 320, 256, params, 5e4);
}

double last_frame_s(const RunResults& r, const std::string& key) {
  const double rate = stats_number(r, key, "pxpl5.last_frame_per_second");
  if (!(rate > 0)) throw MeasureError("run " + key + " has no frame rate");
  return 1.0 / rate;
}

/// Six frames of Fig. 9's system on the teapot filling the screen, the camera turning a degree a
/// frame, with `in_flight` frames in the pipeline (L270).
RunRequest pipeline_run(std::string key, int in_flight, const std::vector<std::string>& extra) {
  std::vector<std::string> params = {"sampling.finest=4",
                                     "sampling.start=16",
                                     "frames=6",
                                     "camera.spin=1",
                                     "camera.distance=0.5",
                                     "pipeline.frames_in_flight=" + std::to_string(in_flight)};
  params.insert(params.end(), extra.begin(), extra.end());
  return machine_run_request(std::move(key), kPxpl5Machine, "builtin:spd-teapot", 640, 512, params,
                             6e5);
}

/// The run's steady frame rate: the frames after the first over the time between their displays.
double steady_fps(const RunResults& r, const std::string& key) {
  const double rate = stats_number(r, key, "frame_sequence.steady_frames_per_second");
  if (!(rate > 0)) throw MeasureError("run " + key + " has no steady frame rate");
  return rate;
}

/// The four-frame fill-in (L375): SPD's teapot at 160 x 128, the user moving three frames (the
/// eye turning 5 degrees after each) and resting, with partial updating at `percent`; the image
/// written is that of frame `shown` (display.frame).
RunRequest fill_in_run(std::string key, int percent, int rest, int shown) {
  return machine_run_request(
      std::move(key), kPxpl5Machine, "builtin:spd-teapot", 160, 128,
      {"camera.path=move 3, rest " + std::to_string(rest), "camera.spin=5",
       "update.fraction=" + std::to_string(percent), "display.frame=" + std::to_string(shown)},
      2e4);
}

/// The bytes of a run's image.png.
std::string image_bytes(const RunResults& r, const std::string& key) {
  const auto it = r.find(key);
  if (it == r.end() || !it->second.failure.empty())
    throw MeasureError("run " + key + " did not finish");
  std::ifstream in(it->second.out_dir / "image.png", std::ios::binary);
  if (!in) throw MeasureError("run " + key + " wrote no image.png");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

double frame_s(const RunResults& r, const std::string& key) {
  return stats_number(r, key, "simulated_time_s");
}

}  // namespace

namespace {
/// What the cost order's gain (L360) rests on: the master's and the casters' costs, and when
/// the next frame's regions are handed out.
std::vector<AssumptionRef> order_assumptions() {
  return {{.param = "master.assign_time"},
          {.param = "gp.clock"},
          {.param = "compositor.sample_time"},
          {.param = "master.next_frame"}};
}

/// Rows against squares (Fig. 9): the casters' and the master's costs, and the threshold.
std::vector<AssumptionRef> sampling_assumptions() {
  return {{.param = "gp.clock"},
          {.param = "master.assign_time"},
          {.param = "sampling.threshold"},
          {.param = "wire.sample_bytes"}};
}

/// The pipelined renderer (L270): the back end's costs and how many frames are let in.
std::vector<AssumptionRef> pipeline_assumptions() {
  return {{.param = "compositor.sample_time"},
          {.param = "renderer.tile_time"},
          {.param = "pipeline.frames_in_flight",
           .values = {"3", "4"},
           .why = "more frames in flight (1 serialises them, which X6a compares against)"},
          {.param = "master.next_frame"}};
}

/// All nodes by-passed (Fig. 4): the ring carries the samples.
std::vector<AssumptionRef> ring_assumptions() {
  return {{.param = "ring.hop_latency"},
          {.param = "wire.sample_bytes"},
          {.param = "compositor.sample_time"},
          {.param = "frame_buffer.pixel_time"}};
}

/// The master alone (Fig. 5): its cost a region, and the casters' clock.
std::vector<AssumptionRef> master_assumptions() {
  return {{.param = "master.assign_time"}, {.param = "gp.clock"}};
}

/// The back end (Fig. 6): compositors, renderers and the frame buffer.
std::vector<AssumptionRef> back_end_assumptions() {
  return {{.param = "compositor.sample_time"},
          {.param = "renderer.tile_time"},
          {.param = "wire.sample_bytes"},
          {.param = "frame_buffer.pixel_time"}};
}

void add_pxpl5_figures(Plan& plan, const PlanOptions&) {
  // The runs take about a second each at full size, so quick mode runs them as they are.
  const std::string vol2 =
      "builtin:spd-teapot at 640 x 512, Fig. 9's 21 GPs (16 casters, 4 "
      "compositors, a master), 80 squares sampled 16 x 16 to 4 x 4, "
      "second frame";
  // X1 over six setups (L360): the gain of the cost order, reported as a band; the verdict is
  // on the median.
  std::vector<std::pair<std::string, std::string>> orders;  // (screen run, cost run) by setup
  std::vector<std::string> order_runs;
  const std::vector<OrderSetup> setups = order_setups();
  for (std::size_t k = 0; k < setups.size(); ++k) {
    const auto key = [&](const char* order) {
      return k == 0 ? std::string("pxpl5-") + order + "-order"
                    : "pxpl5-x1-" + std::to_string(k) + "-" + order;
    };
    auto screen_params = setups[k].params, cost_params = setups[k].params;
    screen_params.push_back("assign.order=screen");
    cost_params.push_back("assign.order=cost");
    orders.emplace_back(plan.add_run(vol2_run(key("screen"), screen_params, setups[k].scene)),
                        plan.add_run(vol2_run(key("cost"), cost_params, setups[k].scene)));
    order_runs.push_back(orders.back().first);
    order_runs.push_back(orders.back().second);
  }
  const std::string cost = orders.front().second;  // the teapot filling the screen, by cost
  plan.figures.push_back(Figure{
      .id = "X1",
      .title = "Squares in descending previous-frame cost against screen order, median of six "
               "setups",
      .seed_ref = "seed 004 L360",
      .seed_text = "\"Typically, assignment of squares on the basis of descending cost provides "
                   "approximately 10-20% increase in frame rate over distribution in screen "
                   "order\"",
      .seed_value = 0.15,
      .seed_display = "+10% to +20%",
      .unit = "",
      .tolerance = Tolerance::range(0.10, 0.20,
                                    "VOL2's range as stated, for its typical volume data; the "
                                    "gain grows as the squares' costs grow more uneven, so the "
                                    "verdict is on the median of six setups"),
      .workload = "Fig. 9's 21 GPs at 640 x 512, 80 squares sampled 16 x 16 to 4 x 4, the "
                  "camera turning a degree, second frame; builtin:spd-teapot at "
                  "camera.distance 0.5, 0.75 and 1, builtin:default, npp-412 and ullner-cubes "
                  "at their views",
      .runs = order_runs,
      .measure =
          [orders, setups](const RunResults& r) {
            std::vector<double> gains;
            std::string each;
            for (std::size_t k = 0; k < orders.size(); ++k) {
              const double g =
                  last_frame_s(r, orders[k].first) / last_frame_s(r, orders[k].second) - 1.0;
              gains.push_back(g);
              each += (k ? "; " : "") + setups[k].label + " " + format_number(100 * g) + "%";
            }
            std::vector<double> sorted = gains;
            std::sort(sorted.begin(), sorted.end());
            const std::size_t n = sorted.size();
            const double median = n % 2 ? sorted[n / 2] : (sorted[n / 2 - 1] + sorted[n / 2]) / 2;
            return Measured{median, "frame rate gain: median " + format_number(100 * median) +
                                        "%, range " + format_number(100 * sorted.front()) +
                                        "% to " + format_number(100 * sorted.back()) + "% (" +
                                        each + ")"};
          },
      .figure_class = FigureClass::kMeasured,
      .assumptions = order_assumptions(),
  });

  // Fig. 9 (L369-L371): rows a ray every 4 x 4 against adaptive squares, full screen and about
  // 1/16 coverage (the rows measure 97% and 6.7%: pxpl5.screen_coverage).
  const std::string full_rows =
      plan.add_run(vol2_run("pxpl5-full-rows", {"camera.distance=0.5", "assign.scheme=rows"}));
  const std::string far_rows =
      plan.add_run(vol2_run("pxpl5-far-rows", {"camera.distance=2.5", "assign.scheme=rows"}));
  const std::string far_squares =
      plan.add_run(vol2_run("pxpl5-far-squares", {"camera.distance=2.5"}));
  // num's frame time over den's (den's rate over num's); the coverage the rows run measures.
  const auto ratio = [](const std::string& num, const std::string& den, const std::string& rows,
                        const char* what) {
    return [num, den, rows, what](const RunResults& r) {
      const double a = last_frame_s(r, num), b = last_frame_s(r, den);
      return Measured{a / b,
                      std::string(what) + ": " + format_number(1.0 / b) + " against " +
                          format_number(1.0 / a) + " frames/s; coverage " +
                          format_number(100 * stats_number(r, rows, "pxpl5.screen_coverage")) +
                          "% (rows' rays that hit)"};
    };
  };
  plan.figures.push_back(Figure{
      .id = "X2a",
      .title = "Full screen: sample squares' frame rate over sample rows'",
      .seed_ref = "seed 004 L371",
      .seed_text = "squares give \"better performance for full-screen images\" (Fig. 9: full "
                   "screen at 5 cm viewpoint distance)",
      .seed_value = 1.0,
      .seed_display = "squares / rows > 1",
      .unit = "",
      .tolerance = Tolerance::above(1.0, "qualitative: Fig. 9's curves carry no numbers"),
      .workload = vol2 + "; the teapot filling the screen (camera.distance 0.5)",
      .runs = {full_rows, cost},
      .measure = ratio(full_rows, cost, full_rows, "squares against rows"),
      .figure_class = FigureClass::kQualitative,
      .assumptions = sampling_assumptions(),
  });
  plan.figures.push_back(Figure{
      .id = "X2b",
      .title = "Low coverage: sample rows' frame rate over sample squares'",
      .seed_ref = "seed 004 L371",
      .seed_text = "rows give \"better performances for images with low screen coverage\" (Fig. "
                   "9: 60 cm gives about 1/16 coverage)",
      .seed_value = 1.0,
      .seed_display = "rows / squares > 1",
      .unit = "",
      .tolerance = Tolerance::above(1.0, "qualitative: Fig. 9's curves carry no numbers"),
      .workload = vol2 + "; the eye 2.5 times as far (about 1/16 of the screen covered)",
      .runs = {far_squares, far_rows},
      .measure = ratio(far_squares, far_rows, far_rows, "rows against squares"),
      .figure_class = FigureClass::kQualitative,
      .assumptions = sampling_assumptions(),
  });

  // Fig. 9's consistency (L371): over the distances from full screen (0.5) to about 1/16 of it
  // (2.5), the spread of each scheme's frame rate, fastest over slowest.
  const std::vector<std::string> distances = {"0.5", "0.75", "1", "1.5", "2", "2.5"};
  std::vector<std::string> rows_runs, squares_runs;
  for (const std::string& d : distances) {
    rows_runs.push_back(d == "0.5" ? full_rows
                        : d == "2.5"
                            ? far_rows
                            : plan.add_run(vol2_run("pxpl5-rows-" + d, {"camera.distance=" + d,
                                                                        "assign.scheme=rows"})));
    squares_runs.push_back(
        d == "0.5"   ? cost
        : d == "2.5" ? far_squares
                     : plan.add_run(vol2_run("pxpl5-squares-" + d, {"camera.distance=" + d})));
  }
  std::vector<std::string> spread_runs = rows_runs;
  spread_runs.insert(spread_runs.end(), squares_runs.begin(), squares_runs.end());
  plan.figures.push_back(Figure{
      .id = "X2c",
      .title = "Over image sizes: the spread of rows' frame rate over the spread of squares'",
      .seed_ref = "seed 004 L369-L371",
      .seed_text = "squares give \"more consistent frame rates over varied image sizes\" (Fig. "
                   "9: full screen at 5 cm, about 1/16 at 60 cm)",
      .seed_value = 1.0,
      .seed_display = "rows' spread / squares' > 1",
      .unit = "",
      .tolerance = Tolerance::above(1.0, "qualitative: Fig. 9's curves carry no numbers"),
      .workload = vol2 + "; camera.distance 0.5, 0.75, 1, 1.5, 2 and 2.5 (97% to 6.7% of the "
                         "screen covered), rows and squares",
      .runs = spread_runs,
      .measure =
          [rows_runs, squares_runs](const RunResults& r) {
            const auto spread = [&](const std::vector<std::string>& runs) {
              double lo = 0, hi = 0;
              for (const std::string& k : runs) {
                const double rate = 1.0 / last_frame_s(r, k);
                lo = lo == 0 ? rate : std::min(lo, rate);
                hi = std::max(hi, rate);
              }
              return hi / lo;
            };
            const double rows = spread(rows_runs), squares = spread(squares_runs);
            return Measured{rows / squares, "fastest over slowest frame rate: rows " +
                                                format_number(rows) + ", squares " +
                                                format_number(squares)};
          },
      .figure_class = FigureClass::kQualitative,
      .assumptions = sampling_assumptions(),
  });

  // The pipelined renderer (L270): frames in flight against serialised frames.
  const std::string serial = plan.add_run(pipeline_run("pxpl5-serialised", 1, {}));
  const std::string piped = plan.add_run(pipeline_run("pxpl5-pipelined", 2, {}));
  plan.figures.push_back(Figure{
      .id = "X6a",
      .title = "Pipelined frames against serialised ones, no stage saturated: frame rate ratio",
      .seed_ref = "seed 004 L270, L420",
      .seed_text = "VOL2 \"is a pipelined renderer\"; its performance came from the \"pipelined "
                   "system layout\": the back end works on one frame while the casters cast the "
                   "next",
      .seed_value = 1.0,
      .seed_display = "pipelined / serialised > 1",
      .unit = "",
      .tolerance = Tolerance::above(1.0, "qualitative: the seed gives no rates"),
      .workload = vol2 + "; six frames, the teapot filling the screen; 1 and 2 frames in flight",
      .runs = {serial, piped},
      .measure =
          [serial, piped](const RunResults& r) {
            const double s = steady_fps(r, serial), p = steady_fps(r, piped);
            return Measured{p / s, format_number(p) + " against " + format_number(s) +
                                       " frames/s after the first frame"};
          },
      .figure_class = FigureClass::kQualitative,
      .assumptions = pipeline_assumptions(),
  });
  // A saturated stage: the compositors at 20 us a sample (the casters' frame is about 80 ms).
  const std::string slow_back = plan.add_run(
      pipeline_run("pxpl5-pipelined-compositors", 2, {"compositor.sample_time=20 us"}));
  plan.figures.push_back(Figure{
      .id = "X6b",
      .title = "Pipelined, the compositors saturated: frame interval over the busiest "
               "compositor's time a frame",
      .seed_ref = "seed 004 L270, L420",
      .seed_text = "a pipeline's rate is its slowest stage's: with the compositors the slowest, "
                   "a frame every busiest compositor's time a frame",
      .seed_value = 1.0,
      .unit = "",
      .tolerance = Tolerance::relative(0.05,
                                       "a stage that is never idle sets the interval; "
                                       "serialised frames give 1.34"),
      .workload = vol2 + "; six frames, 2 in flight, compositor.sample_time 20 us",
      .runs = {slow_back},
      .measure =
          [slow_back](const RunResults& r) {
            const double interval = 1.0 / steady_fps(r, slow_back);
            const int compositors =
                static_cast<int>(stats_number(r, slow_back, "pxpl5.compositors"));
            const double frames = stats_number(r, slow_back, "pxpl5.frames");
            double busiest = 0;
            for (int k = 0; k < compositors; ++k)
              busiest = std::max(
                  busiest,
                  stats_number(r, slow_back, "modules.compositor" + std::to_string(k) + ".busy_s"));
            const double per_frame = busiest / frames;
            return Measured{interval / per_frame,
                            "interval " + format_number(interval * 1e3) +
                                " ms after the first frame; the busiest compositor " +
                                format_number(per_frame * 1e3) + " ms a frame"};
          },
      .figure_class = FigureClass::kMeasured,
      .assumptions = pipeline_assumptions(),
  });

  // Partial updating fills the image in (L375): the first frame at the resting view whose
  // displayed image is the fully updated one.
  for (const auto& [id, percent, seed] : {std::tuple{"X7a", 25, 4}, std::tuple{"X7b", 50, 2}}) {
    const int rest = seed + 1;
    // Frames 0-2 move; frame 3 is the first at the resting view, frame 2 + k the k-th.
    const std::string full = plan.add_run(
        fill_in_run("pxpl5-fill-full-" + std::to_string(percent), 100, rest, 2 + rest));
    std::vector<std::string> shown;
    for (int k = 1; k <= rest; ++k)
      shown.push_back(plan.add_run(
          fill_in_run("pxpl5-fill-" + std::to_string(percent) + "-" + std::to_string(k), percent,
                      rest, 2 + k)));
    std::vector<std::string> runs = shown;
    runs.push_back(full);
    plan.figures.push_back(Figure{
        .id = id,
        .title = "Partial updating at " + std::to_string(percent) +
                 "%: the frame at the resting view whose image is complete",
        .seed_ref = "seed 004 L375-L377",
        .seed_text = "\"if the partial updating fraction is 25%, each sample is updated once every "
                     "4 frames. When user interaction pauses, an image at the lowest successive "
                     "refinement level will have filled in after four frames\"" +
                     std::string(percent == 50 ? " (at 50%: every 2 frames)" : ""),
        .seed_value = static_cast<double>(seed),
        .unit = "frames",
        .tolerance = Tolerance::absolute(0.0, "a count of frames, which the schedule makes exact"),
        .workload = "builtin:spd-teapot at 160 x 128, camera.path \"move 3, rest " +
                    std::to_string(rest) + "\" (5 degrees a move), update.fraction " +
                    std::to_string(percent) +
                    ", each frame at the resting view displayed "
                    "against the same view fully updated (100%)",
        .runs = runs,
        .measure =
            [shown, full](const RunResults& r) {
              const std::string want = image_bytes(r, full);
              std::string differs;
              for (std::size_t k = 0; k < shown.size(); ++k) {
                if (image_bytes(r, shown[k]) == want)
                  return Measured{static_cast<double>(k + 1),
                                  "frames at the resting view before it differ from the "
                                  "complete image: " +
                                      (differs.empty() ? std::string("none") : differs)};
                differs += (differs.empty() ? "" : ", ") + std::to_string(k + 1);
              }
              throw MeasureError("no frame at the resting view shows the complete image");
            },
        // The frame that completes is 1 / the update fraction: the schedule's arithmetic.
        .figure_class = FigureClass::kDerived,
    });
  }

  // By-pass code (L333-L350).
  const std::string scene = "builtin:default";
  const std::string all4 =
      plan.add_run(bypass_run("pxpl5-bypass-all-4", scene, {"bypass=all", "caster_count=4"}));
  const std::string all48 =
      plan.add_run(bypass_run("pxpl5-bypass-all-48", scene, {"bypass=all", "caster_count=48"}));
  plan.figures.push_back(Figure{
      .id = "X3",
      .title = "All nodes by-passed: frame time with 48 casters over 4",
      .seed_ref = "seed 004 L344",
      .seed_text = "Fig. 4: the pipeline's maximum throughput is \"independent of the number of "
                   "computing nodes\"",
      .seed_value = 1.0,
      .unit = "",
      .tolerance = Tolerance::relative(0.1, "Fig. 4's flat lines, read as within 10%"),
      .workload = "builtin:default at 320 x 256, squares, bypass=all",
      .runs = {all4, all48},
      .measure =
          [all4, all48](const RunResults& r) {
            return Measured{frame_s(r, all48) / frame_s(r, all4),
                            format_number(frame_s(r, all48) * 1e3) + " ms against " +
                                format_number(frame_s(r, all4) * 1e3) + " ms"};
          },
      .figure_class = FigureClass::kMeasured,
      .assumptions = ring_assumptions(),
  });
  const std::string all4_coarse = plan.add_run(bypass_run(
      "pxpl5-bypass-all-4-coarse", scene, {"bypass=all", "caster_count=4", "sampling.finest=4"}));
  plan.figures.push_back(Figure{
      .id = "X3b",
      .title = "All nodes by-passed: frame rate with a ray every 4 x 4 pixels over every pixel",
      .seed_ref = "seed 004 L344",
      .seed_text = "Fig. 4: the pipeline's maximum throughput \"at different image sampling "
                   "resolutions\": coarser sampling, fewer samples to pass, a higher rate",
      .seed_value = 1.0,
      .seed_display = "> 1",
      .unit = "",
      .tolerance = Tolerance::above(1.0, "qualitative: Fig. 4 carries no numbers"),
      .workload = "builtin:default at 320 x 256, squares, bypass=all, 4 casters, "
                  "sampling.finest 1 and 4",
      .runs = {all4, all4_coarse},
      .measure =
          [all4, all4_coarse](const RunResults& r) {
            return Measured{frame_s(r, all4) / frame_s(r, all4_coarse),
                            format_number(frame_s(r, all4) * 1e3) + " ms at every pixel, " +
                                format_number(frame_s(r, all4_coarse) * 1e3) +
                                " ms at a ray every 4 x 4"};
          },
      .figure_class = FigureClass::kQualitative,
      .assumptions = ring_assumptions(),
  });
  const std::string master1 =
      plan.add_run(bypass_run("pxpl5-bypass-master-1", scene,
                              {"bypass=all-but-master", "assign.scheme=rows", "caster_count=1"}));
  const std::string master48 =
      plan.add_run(bypass_run("pxpl5-bypass-master-48", scene,
                              {"bypass=all-but-master", "assign.scheme=rows", "caster_count=48"}));
  plan.figures.push_back(Figure{
      .id = "X4a",
      .title = "All but the master by-passed: frame rate with 48 casters over 1",
      .seed_ref = "seed 004 L347",
      .seed_text = "Fig. 5: \"with few casters the frame rate is low\" (per-region processing on "
                   "one caster); it rises with the casters",
      .seed_value = 1.0,
      .seed_display = "> 1",
      .unit = "",
      .tolerance = Tolerance::above(1.0, "qualitative: Fig. 5 carries no numbers"),
      .workload = "builtin:default at 320 x 256, sample rows, bypass=all-but-master",
      .runs = {master1, master48},
      .measure =
          [master1, master48](const RunResults& r) {
            return Measured{frame_s(r, master1) / frame_s(r, master48),
                            format_number(frame_s(r, master1) * 1e3) + " ms with 1, " +
                                format_number(frame_s(r, master48) * 1e3) + " ms with 48"};
          },
      .figure_class = FigureClass::kQualitative,
      .assumptions = master_assumptions(),
  });
  plan.figures.push_back(Figure{
      .id = "X4b",
      .title = "All but the master by-passed, 48 casters: the master GP's busy share",
      .seed_ref = "seed 004 L347",
      .seed_text = "Fig. 5: with many casters the frame rate is \"the master GP's maximum speed\"",
      .seed_value = 1.0,
      .seed_display = "> 0.85",
      .unit = "",
      .tolerance = Tolerance::above(0.85, "the master sets the pace: busy most of the frame"),
      .workload = "as X4a, 48 casters",
      .runs = {master48},
      .measure =
          [master48](const RunResults& r) {
            return Measured{stats_number(r, master48, "modules.master.utilization"),
                            "stats.json modules.master.utilization"};
          },
      .figure_class = FigureClass::kQualitative,
      .assumptions = master_assumptions(),
  });
  const std::string back =
      plan.add_run(bypass_run("pxpl5-bypass-back", scene, {"bypass=casters-and-master"}));
  const std::string back40 = plan.add_run(
      bypass_run("pxpl5-bypass-back-40", scene, {"bypass=casters-and-master", "caster_count=40"}));
  const std::string back_teapot = plan.add_run(
      bypass_run("pxpl5-bypass-back-teapot", "builtin:spd-teapot", {"bypass=casters-and-master"}));
  const Tolerance flat = Tolerance::relative(0.05, "Fig. 6: independent, read as within 5%");
  plan.figures.push_back(Figure{
      .id = "X5a",
      .title = "Back end (casters and master by-passed): 40 casters over 16",
      .seed_ref = "seed 004 L350",
      .seed_text = "Fig. 6: the back end is independent of node count",
      .seed_value = 1.0,
      .unit = "",
      .tolerance = flat,
      .workload = "builtin:default at 320 x 256, bypass=casters-and-master",
      .runs = {back, back40},
      .measure =
          [back, back40](const RunResults& r) {
            return Measured{frame_s(r, back40) / frame_s(r, back), "frame time ratio"};
          },
      .figure_class = FigureClass::kMeasured,
      .assumptions = back_end_assumptions(),
  });
  const std::string back_large = plan.add_run(machine_run_request(
      "pxpl5-bypass-back-640", kPxpl5Machine, scene, 640, 512, {"bypass=casters-and-master"}, 2e5));
  plan.figures.push_back(Figure{
      .id = "X5b",
      .title = "Back end (casters and master by-passed): 640 x 512 over 320 x 256",
      .seed_ref = "seed 004 L337, L350",
      .seed_text = "the back end's performance \"depends mostly on image resolution\" (L337; "
                   "Fig. 6)",
      .seed_value = 1.0,
      .seed_display = "> 1",
      .unit = "",
      .tolerance = Tolerance::above(1.0, "qualitative: Fig. 6 carries no numbers"),
      .workload = "builtin:default, bypass=casters-and-master, 320 x 256 and 640 x 512",
      .runs = {back, back_large},
      .measure =
          [back, back_large](const RunResults& r) {
            return Measured{frame_s(r, back_large) / frame_s(r, back),
                            "frame time ratio (four times the pixels)"};
          },
      .figure_class = FigureClass::kQualitative,
      .assumptions = back_end_assumptions(),
  });
  plan.figures.push_back(Figure{
      .id = "X5c",
      .title = "Back end: SPD's teapot over builtin:default (by construction)",
      .seed_ref = "seed 004 L337",
      .seed_text = "compositing performance \"is fairly independent of image content\"",
      .seed_value = 1.0,
      .unit = "",
      .tolerance = flat,
      .workload = "320 x 256, bypass=casters-and-master, two scenes",
      .runs = {back, back_teapot},
      .measure =
          [back, back_teapot](const RunResults& r) {
            return Measured{frame_s(r, back_teapot) / frame_s(r, back),
                            "frame time ratio; by-passed casters send samples of no radiance, "
                            "so the back end sees no content"};
          },
      .figure_class = FigureClass::kDerived,
  });
}

const RegisterFigures kRegistered(kPxpl5Machine, add_pxpl5_figures);

}  // namespace

}  // namespace rtsim::validation
