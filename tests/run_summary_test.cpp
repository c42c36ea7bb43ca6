// What `rtsim run` prints (app/run_summary.hpp) and the number formats it uses
// (app/number_text.hpp): engineering units, modules by utilisation, the bottleneck, the overhead.
#include "app/run_summary.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "app/bottleneck.hpp"
#include "app/number_text.hpp"

using rtsim::app::format_percent;
using rtsim::app::format_run_summary;
using rtsim::app::format_seconds;
using rtsim::app::format_significant;

TEST(NumberText, SecondsInEngineeringUnitsWithFourSignificantDigits) {
  EXPECT_EQ(format_seconds(5.52977e-05), "55.30 µs");
  EXPECT_EQ(format_seconds(0.22651), "226.5 ms");
  EXPECT_EQ(format_seconds(1.5), "1.500 s");
  EXPECT_EQ(format_seconds(9062.35), "2.517 h");  // the VAX's frame, not "9062.35 s"
  EXPECT_EQ(format_seconds(132340.0), "36.76 h");
  EXPECT_EQ(format_seconds(90.0), "1.500 min");
  EXPECT_EQ(format_seconds(4.8e-9), "4.800 ns");
  EXPECT_EQ(format_seconds(0.99996e-3), "1.000 ms");  // rounded before the unit is chosen
  EXPECT_EQ(format_seconds(-2.67696e-21), "0 s");     // below SystemC's picosecond: rounding
  EXPECT_EQ(format_seconds(0.0), "0 s");
  EXPECT_EQ(format_significant(999.96), "1000");
  EXPECT_EQ(format_significant(0.00012346), "0.0001235");
  EXPECT_EQ(format_percent(0.99994), "100.0%");
  EXPECT_EQ(format_percent(0.138), "13.8%");
}

namespace {

nlohmann::json stats_of_a_run() {
  return nlohmann::json::parse(R"({
    "machine": "a-machine", "scene": "builtin:ullner-cubes", "width": 64, "height": 64,
    "simulated_time_s": 1.388, "wall_time_s": 0.1361,
    "functional_wall_time_s": 0.004538, "overhead_ratio": 29.99,
    "modules": {
      "host": {"busy_s": 0.0167, "utilization": 0.012, "waiting_for_data_s": 1.3714,
               "blocked_s": 0.0},
      "host.ray_link": {"busy_s": 0.019, "utilization": 0.014},
      "peripheral.pipeline": {"busy_s": 1.388, "utilization": 0.99991},
      "peripheral.lighting": {"busy_s": 0.0097, "utilization": 0.007},
      "queue.rays": {"mean_occupancy": 3.2}
    },
    "ray_latency_s": {"count": 4096, "mean": 5.52977e-05, "p50": 5.52e-05, "p99": 5.54e-05},
    "latency_probe": {"unattributed_s": -2.67696e-21, "stages": {
      "host": {"total_s": 1.2e-6, "share": 0.02},
      "peripheral.pipeline": {"total_s": 5.1e-5, "share": 0.93}}}
  })");
}

}  // namespace

TEST(NumberText, ANameEndingInSecondsHoldsSecondsButARatePerSecondDoesNot) {
  using rtsim::app::format_figure;
  using rtsim::app::names_seconds;
  EXPECT_TRUE(names_seconds("simulated_time_s"));
  EXPECT_TRUE(names_seconds("ray_latency_s.p99"));
  EXPECT_FALSE(names_seconds("throughput_rpi_per_s"));  // was shown as "254.4 h"
  EXPECT_FALSE(names_seconds("rays_per_s.mean"));
  EXPECT_FALSE(names_seconds("ray_latency_s.count"));  // was shown as "37.77 h"
  EXPECT_EQ(format_figure("ray_latency_s.count", 2084), "2084");
  EXPECT_EQ(format_figure("throughput_rpi_per_s", 915751.3), "915751");  // not "254.4 h"
  EXPECT_EQ(format_figure("chain_utilization", 0.07613), "7.6%");
  EXPECT_EQ(format_figure("modules.host.utilization", 1.0), "100.0%");
  EXPECT_EQ(format_figure("along_chain_s", 1.8360044137546107e-06), "1.836 µs");
  EXPECT_EQ(format_figure("mean_ray_travel", 0.00001234), "0.00001234");  // no exponent
  EXPECT_FALSE(names_seconds("intersections"));
}

TEST(RunSummary, ModulesByUtilisationBottleneckOverheadAndNoExponents) {
  const std::string text =
      format_run_summary(stats_of_a_run(), {{"image", "out/run/image.png"}, {"stats", "s.json"}});
  std::cout << text;
  EXPECT_NE(text.find("frame time 1.388 s simulated, 136.1 ms wall"), std::string::npos);
  // Busiest first, not by name.
  const auto pipeline = text.find("peripheral.pipeline 100.0%");
  const auto ray_link = text.find("host.ray_link 1.4%");
  const auto host = text.find("host 1.2%");
  ASSERT_NE(pipeline, std::string::npos);
  EXPECT_LT(pipeline, ray_link);
  EXPECT_LT(ray_link, host);
  // The bottleneck, and who waits for it.
  EXPECT_NE(text.find("bottleneck  peripheral.pipeline, 100.0% busy: host waits 98.8% of the "
                      "frame"),
            std::string::npos);
  EXPECT_NE(text.find("ray latency mean 55.30 µs, p50 55.20 µs, p99 55.40 µs"), std::string::npos);
  // Stages by their share; rounding noise is 0.
  EXPECT_LT(text.find("peripheral.pipeline 51.00 µs (93.0%)"), text.find("host 1.200 µs (2.0%)"));
  EXPECT_NE(text.find("unattributed 0 s"), std::string::npos);
  EXPECT_NE(text.find("overhead    30.0x the functional render of the same frame (4.538 ms wall)"),
            std::string::npos);
  EXPECT_NE(text.find("  image       out/run/image.png\n"), std::string::npos);
  EXPECT_EQ(text.find("e-"), std::string::npos) << "a number in e-notation";
  EXPECT_EQ(text.find("e+"), std::string::npos) << "a number in e-notation";
}

TEST(RunSummary, ASampledRunsHeadlineCarriesItsIntervalAndScope) {
  auto stats = stats_of_a_run();
  stats["sample"] = {{"every", 4},
                     {"window_rows", 8},
                     {"windows", 32},
                     {"detailed_windows", 9},
                     {"detailed_frame_s", 0.5},
                     {"estimate_s", 1.388},
                     {"ci99_7_s", {1.338, 1.438}},
                     {"half_width_relative", 0.036}};
  const std::string text = format_run_summary(stats, {});
  EXPECT_NE(text.find("frame time 1.388 s +- 50.00 ms (estimated, 99.7%) simulated"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("(busy, bottleneck and latency figures cover the 9 of 32 windows simulated "
                      "in detail (500.0 ms simulated))"),
            std::string::npos)
      << text;
  // In full detail: neither.
  const std::string full = format_run_summary(stats_of_a_run(), {});
  EXPECT_EQ(full.find("estimated"), std::string::npos);
  EXPECT_EQ(full.find("windows simulated in detail"), std::string::npos);
}

TEST(RunSummary, NoSaturatedModuleIsSaidSo) {
  auto stats = stats_of_a_run();
  stats["modules"]["peripheral.pipeline"]["utilization"] = 0.838;
  const std::string text = format_run_summary(stats, {});
  EXPECT_NE(text.find("bottleneck  none saturated: the busiest, peripheral.pipeline, is 83.8% "
                      "busy; latency, dependencies and bursts of work set the frame"),
            std::string::npos)
      << text;
}

// With nothing saturated, the line says where the work spent its time, by class of module:
// queued (mean occupancy x frame), busy, or waiting for what a module names.
TEST(RunSummary, WithNothingSaturatedItSaysWhereTheTimeWent) {
  const auto stats = nlohmann::json::parse(R"({
    "machine": "m", "scene": "s", "width": 8, "height": 8, "simulated_time_s": 2.0,
    "modules": {
      "node0": {"busy_s": 0.6, "utilization": 0.3, "memory_waited_s": 0.2},
      "node1": {"busy_s": 0.8, "utilization": 0.4},
      "node0.in_e": {"queue": {"mean_occupancy": 0.5}},
      "node1.in_w": {"queue": {"mean_occupancy": 1.0}},
      "node0.link_e": {"busy_s": 0.2, "utilization": 0.1, "waited_s": 0.2}
    }})");
  const rtsim::app::Bottleneck b = rtsim::app::find_bottleneck(stats);
  EXPECT_FALSE(b.saturated);
  ASSERT_EQ(b.time.size(), 5u);
  EXPECT_EQ(b.time[0].where, "node*.in_* queued");  // (0.5 + 1.0) x 2 s
  EXPECT_DOUBLE_EQ(b.time[0].seconds, 3.0);
  EXPECT_EQ(b.time[1].where, "node* busy");
  EXPECT_DOUBLE_EQ(b.time[1].seconds, 1.4);
  EXPECT_DOUBLE_EQ(b.time[0].share, 3.0 / 5.0);
  const std::string text = format_run_summary(stats, {});
  EXPECT_NE(text.find("the work's time: node*.in_* queued 60.0%, node* busy 28.0%"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("node* waiting for memory"), std::string::npos) << text;
}

// `rtsim run` hands the summary its document as built (nlohmann::ordered_json) through a view
// without the modules' utilisation series: the text is the same as from the whole document,
// and the view keeps every key but those series (the queue's occupancy, the waits, the busy).
TEST(RunSummary, TheDocumentAsBuiltGivesTheSameTextThroughItsView) {
  auto whole = nlohmann::json::parse(R"({
    "machine": "m", "scene": "s", "width": 8, "height": 8, "simulated_time_s": 2.0,
    "wall_time_s": 0.5, "overhead_ratio": 12.5, "functional_wall_time_s": 0.04,
    "ray_latency_s": {"count": 64, "mean": 1e-3, "p50": 1e-3, "p99": 2e-3},
    "modules": {
      "node10": {"busy_s": 0.6, "utilization": 0.3, "memory_waited_s": 0.2,
                 "utilization_windows": {"begin_s": 0, "window_s": 1, "values": [0.2, 0.4]}},
      "node2": {"busy_s": 0.8, "utilization": 0.4, "blocked_s": 0.1},
      "node2.in_e": {"queue": {"mean_occupancy": 0.5, "capacity": 4}},
      "node10.link_w": {"busy_s": 0.2, "utilization": 0.1, "waited_s": 0.2}
    }})");
  const auto as_built = nlohmann::ordered_json::parse(whole.dump());
  const nlohmann::json view = rtsim::app::summary_view(as_built);
  EXPECT_FALSE(view["modules"]["node10"].contains("utilization_windows"));
  auto expected = whole;
  expected["modules"]["node10"].erase("utilization_windows");
  EXPECT_EQ(view, expected);
  for (const double u : {0.3, 0.99}) {  // nothing saturated (where the time went) and saturated
    whole["modules"]["node2"]["utilization"] = u;
    auto built = nlohmann::ordered_json::parse(whole.dump());
    const std::string text = format_run_summary(built, {{"stats", "s.json"}});
    EXPECT_EQ(text, format_run_summary(whole, {{"stats", "s.json"}}));
    EXPECT_NE(text.find(u < 0.5 ? "node*.in_* queued" : "node2, 99.0% busy"), std::string::npos)
        << text;
  }
}

// A sequence of frames (pxpl5-raytrace with frames > 1): the heading counts them, and a line
// gives the frame rate and latency, then each frame's start, display, latency and interval.
TEST(RunSummary, ASequenceOfFramesGivesItsRateAndEachFrame) {
  auto stats = stats_of_a_run();
  nlohmann::json per = nlohmann::json::array();
  for (int f = 0; f < 14; ++f)
    per.push_back({{"frame", f},
                   {"start_s", 0.1 * f},
                   {"display_s", 0.1 * f + 0.15},
                   {"latency_s", 0.15},
                   {"interval_s", f == 0 ? 0.15 : 0.1}});
  stats["frame_sequence"] = {{"frames", 14},
                             {"frames_per_second", 9.5238},
                             {"steady_frames_per_second", 10.0},
                             {"last_frame_per_second", 10.0},
                             {"latency_mean_s", 0.15},
                             {"latency_max_s", 0.15},
                             {"per_frame", per}};
  const std::string text = format_run_summary(stats, {});
  std::cout << text;
  EXPECT_NE(text.find("14 frames in 1.388 s simulated"), std::string::npos) << text;
  EXPECT_EQ(text.find("frame time"), std::string::npos);
  EXPECT_NE(text.find("frames      14 at 9.52 frames/s (after the first 10.0, the last 10.0); "
                      "latency mean 150.0 ms, max 150.0 ms"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("frame 3     start 300.0 ms, displayed 450.0 ms, latency 150.0 ms, "
                      "interval 100.0 ms"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("frame 12 "), std::string::npos);  // the first twelve, then a count
  EXPECT_NE(text.find("(2 more in stats.json frame_sequence)"), std::string::npos);
}
