// Ullner's hidden-line elimination pipeline (seed 000 §3.4, L1679-L1914; note 000-ch3 §2.10): the
// message time on the 500 ns bit-serial links (L1906), the delay of a segment through 10,000
// plane processors and the polygons a thirtieth of a second holds (L1914), utilisation along the
// pipe (L1914), and the drawn lines against an independent check (L1681).
#include <algorithm>
#include <string>
#include <vector>

#include "platform/validation/figure_registry.hpp"

namespace rtsim::validation {

namespace {

constexpr const char* kHiddenLine = "ullner-hidden-line";

/// A run of the pipe; its cost grows with segments x processors.
RunRequest pipe_run(const std::string& key, const std::string& scene, int side,
                    const std::vector<std::string>& params, double cost) {
  return machine_run_request(key, kHiddenLine, scene, side, side, params, cost);
}

double number(const RunResults& r, const std::string& key, const std::string& path) {
  return stats_number(r, key, "hidden_line." + path);
}

void add_hidden_line_figures(Plan& plan, const PlanOptions& options) {
  const bool quick = options.quick;
  // L1914's pipe: "10,000 plane processors ... enough to handle 2,000 polygons" of four sides.
  // builtin:ullner-random-2000 is 2,000 random squares; seen from its camera 9,841 planes are in
  // front of the eye, and pipe.plane_processors = 10000 makes the pipe the seed's length (the
  // same run in quick mode: about 15 s, and half the squares would leave half the pipe idle,
  // which HL4 would see).
  const std::string full_pipe = plan.add_run(
      pipe_run("hl-2000", "builtin:ullner-random-2000", 256, {"pipe.plane_processors=10000"}, 2e5));
  // The same length of pipe, nearly idle: 100 squares' planes and the rest passing messages on.
  const std::string idle_pipe = plan.add_run(
      pipe_run("hl-idle", "builtin:ullner-random-100", 256, {"pipe.plane_processors=10000"}, 2e4));

  plan.figures.push_back(Figure{
      .id = "HL1",
      .title = "A segment or an intersection message on a link of the pipe",
      .seed_ref = "seed 000 L1906",
      .seed_text = "six wires shared by the segment and intersection messages; \"since each type "
                   "of message includes a 16-bit number, at 500 nanoseconds per bit, it would "
                   "take about 8 usec to transmit a complete message\"",
      .seed_value = 8.0,
      .unit = "us",
      .tolerance = Tolerance::relative(0.01, "16 bit times of 500 ns, one value a wire"),
      .workload = "the message times of the run of HL2b (pipe.link: 6 wires, 500 ns a bit)",
      .runs = {idle_pipe},
      .measure =
          [idle_pipe](const RunResults& r) {
            const double seg = number(r, idle_pipe, "message_time_s.segment") * 1e6;
            const double is = number(r, idle_pipe, "message_time_s.intersection") * 1e6;
            return Measured{std::max(seg, is),
                            "segment " + format_number(seg) + " us, intersection " +
                                format_number(is) + " us, plane " +
                                format_number(number(r, idle_pipe, "message_time_s.plane") * 1e6) +
                                " us"};
          },
      .figure_class = FigureClass::kDerived,
  });

  const std::string latency_tail =
      " (host to divider, every processor a module passing its messages on over its link)";
  plan.figures.push_back(Figure{
      .id = "HL2a",
      .title = "The delay of a segment through 10,000 plane processors, the pipe nearly idle",
      .seed_ref = "seed 000 L1914",
      .seed_text = "\"if the message passing time is the performance bottleneck ... it will take "
                   "about 80 milliseconds ... for a segment to pass through the pipeline\" "
                   "(10,000 processors x 8 us)",
      .seed_value = 80.0,
      .unit = "ms",
      .tolerance = Tolerance::relative(
          0.25,
          "\"about\": a plane processor forwards a segment before it computes (Fig. 3-32), so "
          "an idle processor passes it in one message time (9,500 of them: 76 ms), but each "
          "of the 100 polygons' cleanup processors holds it until the segment behind it "
          "arrives (HL2b), about 15% more here. 625 ns a bit (10 us a message) gives 117 ms "
          "and fails"),
      .workload = "builtin:ullner-random-100 (100 squares: 500 planes) in a pipe of 10,000 plane "
                  "processors, the other 9,500 idle, 256 x 256: the first segment's delay" +
                  latency_tail,
      .runs = {idle_pipe},
      .measure =
          [idle_pipe](const RunResults& r) {
            const double first = number(r, idle_pipe, "segment_latency_s.first") * 1e3;
            return Measured{
                first, "mean over the segments " +
                           format_number(number(r, idle_pipe, "segment_latency_s.mean") * 1e3) +
                           " ms"};
          },
  });
  plan.figures.push_back(Figure{
      .id = "HL2b",
      .title = "The delay of a segment through 10,000 plane processors holding 2,000 squares",
      .seed_ref = "seed 000 L1914",
      .seed_text = "\"if each polygon in the scene had four sides, 10,000 plane processors would "
                   "be enough to handle 2,000 polygons ... about 80 milliseconds ... for a "
                   "segment to pass through the pipeline\"",
      .seed_value = 80.0,
      .unit = "ms",
      .tolerance = Tolerance::relative(0.3,
                                       "the seed's estimate, one message time a processor, "
                                       "with room for the cleanup processors (2,000 more hops)"),
      .workload = "builtin:ullner-random-2000 (9,841 planes in front of the eye) in a pipe of "
                  "10,000 plane processors, 256 x 256: the mean delay over the segments that "
                  "come out" +
                  latency_tail,
      .runs = {full_pipe},
      .measure =
          [full_pipe](const RunResults& r) {
            return Measured{
                number(r, full_pipe, "segment_latency_s.mean") * 1e3,
                "first segment " +
                    format_number(number(r, full_pipe, "segment_latency_s.first") * 1e3) +
                    " ms, frame " + format_number(number(r, full_pipe, "frame_time_s") * 1e3) +
                    " ms"};
          },
      .open = "the seed counts one message time a processor; in Figs. 3-32 and 3-34 a plane "
              "processor holds the intersection it computed until the next message arrives "
              "and sends it ahead of that message, and a cleanup processor holds each segment "
              "until the next segment (or an unmarked intersection) tells it the segment's "
              "intersections are over. So a segment leaves a polygon's cleanup processor only "
              "when the segment behind it arrives there, and a hop costs the pipe's spacing "
              "of segments, not one message time (docs/validation.md)",
  });
  plan.figures.push_back(Figure{
      .id = "HL3",
      .title = "Four-sided polygons processed in a thirtieth of a second",
      .seed_ref = "seed 000 L1914",
      .seed_text = "\"conversely, the machine should be able to process between 800 and 900 "
                   "polygons in a thirtieth of a second\" (1/30 s over 8 us a hop, five plane "
                   "processors a polygon)",
      .seed_value = 850.0,
      .unit = "polygons",
      .tolerance =
          Tolerance::range(800.0, 900.0, "the seed's own range, \"between 800 and 900 polygons\""),
      .workload = "the run of HL2b: its squares in front of the eye, scaled by a thirtieth of a "
                  "second over the frame's time (every segment in, the stream through)",
      .runs = {full_pipe},
      .measure =
          [full_pipe](const RunResults& r) {
            const double polygons = number(r, full_pipe, "polygons");
            const double frame = number(r, full_pipe, "frame_time_s");
            if (!(frame > 0.0)) throw MeasureError(full_pipe + ": no frame time");
            return Measured{
                polygons * (1.0 / 30.0) / frame,
                format_number(polygons) + " polygons in " + format_number(frame * 1e3) + " ms"};
          },
      .open = "as HL2b: each hop costs the spacing of segments, so the frame is several times "
              "the seed's message-passing estimate",
  });

  // L1914: "messages will be eliminated ... causing gaps of idle processors. The delays should
  // tend to close these gaps, thereby maintaining processor utilization."
  plan.figures.push_back(Figure{
      .id = "HL4",
      .title = "Utilisation along the pipe: the least twentieth's link over the busiest's",
      .seed_ref = "seed 000 L1914",
      .seed_text = "\"there are times when a message will be delayed ... but at other times, "
                   "messages will be eliminated ... causing gaps of idle processors. The delays "
                   "should tend to close these gaps, thereby maintaining processor "
                   "utilization\"",
      .seed_value = 1.0,
      .seed_display = "about even",
      .unit = "x",
      .tolerance = Tolerance::range(0.8, 1.0,
                                    "even utilisation along the pipe; a pipe whose far end "
                                    "idles as segments are suppressed falls below 0.8"),
      .workload = "the run of HL2b, its processors in twenty runs first to last",
      .runs = {full_pipe},
      .measure =
          [full_pipe](const RunResults& r) {
            const nlohmann::json& along = stats_of(r, full_pipe)["hidden_line"]["along_pipe"];
            if (!along.is_array() || along.empty()) throw MeasureError(full_pipe + ": no bins");
            double lo = 1e300, hi = 0.0;
            for (const auto& b : along) {
              const double u = b["link_utilization"].get<double>();
              lo = std::min(lo, u);
              hi = std::max(hi, u);
            }
            if (!(hi > 0.0)) throw MeasureError(full_pipe + ": idle links");
            return Measured{lo / hi, "link utilisation " + format_number(lo * 100) + "% to " +
                                         format_number(hi * 100) + "%"};
          },
      .figure_class = FigureClass::kQualitative,
  });

  // L1681: "the results are exact to the numeric precision": the drawn pieces against points
  // tested without the boundary planes.
  struct Check {
    const char* id;
    const char* scene;
    const char* what;
  };
  const std::vector<Check> checks = {
      {"HL5a", "builtin:ullner-cubes", "83 cubes (498 squares)"},
      {"HL5b", "builtin:spd-teapot", "the teapot's 992 triangles on a checkerboard"},
      {"HL5c", "builtin:ullner-random-300", "300 interpenetrating squares"}};
  for (const Check& c : checks) {
    const std::string key =
        plan.add_run(pipe_run(std::string("hl-check-") + c.id, c.scene, quick ? 96 : 256,
                              {"check.points=" + std::string(quick ? "8" : "20")}, 5e4));
    plan.figures.push_back(Figure{
        .id = c.id,
        .title = std::string("Drawn lines against an independent check: ") + c.what,
        .seed_ref = "seed 000 L1681",
        .seed_text = "the visible parts of every edge, \"exact to the numeric precision\"",
        .seed_value = 0.0,
        .seed_display = "none wrong",
        .unit = "points",
        .tolerance = Tolerance::absolute(
            0.0,
            "a point sampled on a segment is tested against every polygon by a 2-D inside "
            "test and its plane's depth in doubles; points within 1e-6 screen units of an "
            "edge or a plane, or of a piece's end, are skipped, everything else must agree"),
        .workload =
            std::string(c.scene) + ", " + (quick ? "8" : "20") + " points a segment (check.points)",
        .runs = {key},
        .measure =
            [key](const RunResults& r) {
              const double missed = number(r, key, "check.missed");
              const double drawn = number(r, key, "check.drawn_hidden");
              return Measured{missed + drawn,
                              format_number(number(r, key, "check.points")) + " points (" +
                                  format_number(number(r, key, "check.hidden")) +
                                  " hidden): " + format_number(missed) + " visible missed, " +
                                  format_number(drawn) + " hidden drawn"};
            },
    });
  }
}

const RegisterFigures kRegistered(kHiddenLine, add_hidden_line_figures);

}  // namespace

}  // namespace rtsim::validation
