// `rtsim sweep --report`: report.html in the sweep's --out, one self-contained page with the
// results table (every point), sweep plots drawn by analysis/sweep_plot.py (real PNGs inline),
// thumbnails of the points' images, the parameters with their sources and the sweep file; failed
// points are listed and do not stop the report; resuming and MPI give a report over every point;
// and the page opens in headless Chromium with every picture decoded and no console message.
// The plots chosen for a table are checked on their own (choose_sweep_plots).
#include "app/sweep_report.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <fstream>

#include "tests/report_test_support.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::chromium;
using rtsim::test::count;
using rtsim::test::image_data;
using rtsim::test::matplotlib_available;
using rtsim::test::open_headless;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using Json = nlohmann::ordered_json;

namespace {

// Three tiny points of the peripheral (16x16, primary rays only): about a second each.
constexpr const char* kGridSweep =
    "name = \"tiny-grid\"\n"
    "machine = \"ullner-peripheral\"\n"
    "scene = \"builtin:ullner-sheets-1000\"\n"
    "width = 16\n"
    "height = 16\n"
    "[params]\n"
    "\"shade.max_depth\" = 0\n"
    "[[axes]]\n"
    "param = \"peripheral.grid.divisions\"\n"
    "values = [2, 4, 8]\n";

// Two points; adder_stages = 2 passes the parameter's bounds but the machine accepts only 1 or 3
// (Fig. 2-17), so point 0001 fails at run time.
constexpr const char* kFailingSweep =
    "machine = \"ullner-peripheral\"\n"
    "scene = \"builtin:ullner-sheets-1000\"\n"
    "width = 8\n"
    "height = 8\n"
    "[params]\n"
    "\"shade.max_depth\" = 0\n"
    "[[axes]]\n"
    "param = \"peripheral.adder_stages\"\n"
    "values = [1, 2]\n";

/// One sweep with --report shared by the tests that read its page.
class SweepReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(scratch_dir("sweep-report"));
    fs::create_directories(*dir_);
    std::ofstream(*dir_ / "grid.toml") << kGridSweep;
    result_ = new rtsim::test::CommandResult(run_rtsim("sweep " + (*dir_ / "grid.toml").string() +
                                                       " --jobs 2 --report --baseline 1 -q --out " +
                                                       (*dir_ / "out").string()));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete result_;
  }
  static fs::path* dir_;
  static rtsim::test::CommandResult* result_;
};
fs::path* SweepReport::dir_ = nullptr;
rtsim::test::CommandResult* SweepReport::result_ = nullptr;

}  // namespace

TEST(SweepReportPlots, ChosenForEachAxisWithSpeedUpForACount) {
  // A gaudet-like sweep: three scenes x pert_count 1..64 (log spaced).
  const auto file = rtsim::sweep::parse_sweep(
      "machine = \"gaudet-pert\"\n"
      "scenes = [\"builtin:npp-412\", \"builtin:npp-816\", \"builtin:npp-820\"]\n"
      "[[axes]]\nparam = \"pert_count\"\n"
      "range = { start = 1, stop = 64, count = 7, scale = \"log\" }\n",
      "speedup.toml", ".");
  rtsim::sweep::ResultsTable t;
  t.columns = {"point",
               "machine",
               "scene",
               "pert_count",
               "status",
               "simulated_time_s",
               "ray_latency_s.mean",
               "point_wall_time_s",
               "modules.a.utilization",
               "modules.b.utilization",
               "modules.idle.utilization",
               "gaudet.shell.time_per_ray_s"};
  int point = 0;
  for (const char* scene : {"builtin:npp-412", "builtin:npp-816", "builtin:npp-820"})
    for (int n : {1, 2, 4, 8, 16, 32, 64})
      t.rows.push_back(
          {point++, "a-machine", scene, n, "ok", 1.0 / n, 1e-5, 2.0, 0.9, 0.5, 0.0, 3e-4});
  const auto plots = rtsim::app::choose_sweep_plots(file, t);
  // One x axis (pert_count; the scene list gives the lines): frame time, speed-up, the per-ray
  // stat, utilisation, latency, wall time.
  ASSERT_EQ(plots.size(), 6u);
  for (const auto& p : plots) {
    EXPECT_EQ(p.x, "pert_count");
    EXPECT_EQ(p.group, "scene");
    EXPECT_TRUE(p.logx) << p.title;  // 1, 2, 4, ..., 64: equal ratios
  }
  EXPECT_EQ(plots[0].y, std::vector<std::string>{"simulated_time_s"});
  EXPECT_TRUE(plots[0].logy);  // 1 .. 1/64
  EXPECT_EQ(plots[1].ratio_to, "pert_count=1");
  EXPECT_EQ(plots[2].y, std::vector<std::string>{"gaudet.shell.time_per_ray_s"});
  // The idle module is left out.
  EXPECT_EQ(plots[3].y,
            (std::vector<std::string>{"modules.a.utilization", "modules.b.utilization"}));
  EXPECT_EQ(plots[4].y, (std::vector<std::string>{"ray_latency_s.mean"}));  // 3 lines: no p99
  EXPECT_EQ(plots[5].y, std::vector<std::string>{"point_wall_time_s"});
  const auto args = plots[1].script_args();
  EXPECT_EQ(args[0], "--x");
  EXPECT_NE(std::find(args.begin(), args.end(), "--ratio-to"), args.end());
  EXPECT_NE(std::find(args.begin(), args.end(), "--logx"), args.end());

  // Nothing succeeded: nothing to plot.
  for (auto& row : t.rows) row[4] = "failed";
  EXPECT_TRUE(rtsim::app::choose_sweep_plots(file, t).empty());
}

TEST(SweepReportPlots, AClassOfInstancesIsDrawnAsItsMeanWithItsRangeShaded) {
  // An array of 4 and of 16 nodes: node3 is another node at each size, so the busiest-module
  // plot draws node* (its mean, min..max shaded), never an instance of it.
  const auto file = rtsim::sweep::parse_sweep(
      "machine = \"ullner-array\"\nscene = \"builtin:ullner-cubes\"\n"
      "[[axes]]\nparam = \"array.rows\"\nvalues = [2, 4]\n",
      "array.toml", ".");
  rtsim::sweep::ResultsTable t;
  t.columns = {"point",
               "machine",
               "scene",
               "array.rows",
               "status",
               "simulated_time_s",
               "modules.host.utilization",
               "modules.node3.utilization",
               "module_classes.node*.utilization.min",
               "module_classes.node*.utilization.mean",
               "module_classes.node*.utilization.max"};
  t.rows.push_back({0, "a-machine", "builtin:ullner-cubes", 2, "ok", 1.0, 0.2, 0.9, 0.1, 0.5, 0.9});
  t.rows.push_back(
      {1, "a-machine", "builtin:ullner-cubes", 4, "ok", 0.5, 0.3, 0.7, 0.05, 0.4, 0.95});
  const auto plots = rtsim::app::choose_sweep_plots(file, t);
  const auto util = std::find_if(plots.begin(), plots.end(), [](const auto& p) {
    return p.title.rfind("Module utilisation", 0) == 0;
  });
  ASSERT_NE(util, plots.end());
  EXPECT_EQ(util->y, (std::vector<std::string>{"module_classes.node*.utilization.mean",
                                               "modules.host.utilization"}));
  ASSERT_EQ(util->bands.size(), 1u);
  EXPECT_EQ(util->bands[0][1], "module_classes.node*.utilization.min");
  const auto args = util->script_args();
  EXPECT_NE(std::find(args.begin(), args.end(),
                      "module_classes.node*.utilization.mean=module_classes.node*.utilization."
                      "min,module_classes.node*.utilization.max"),
            args.end());
}

TEST_F(SweepReport, PageHasEveryRowPlotsImagesAndParameters) {
  if (!matplotlib_available()) GTEST_SKIP() << "no /usr/bin/python3 with matplotlib";
  ASSERT_EQ(result_->exit_code, 0) << result_->output;
  const fs::path out = *dir_ / "out";
  ASSERT_TRUE(fs::exists(out / "report.html"));
  const std::string html = read_file(out / "report.html");
  // Every point's row, with its swept value and status.
  for (const char* row :
       {"<tr><td>0000</td><td>2</td><td>ok</td>", "<tr><td>0001</td><td>4</td><td>ok</td>",
        "<tr><td>0002</td><td>8</td><td>ok</td>"})
    EXPECT_NE(html.find(row), std::string::npos) << row;
  EXPECT_EQ(html.find("Failed points"), std::string::npos);
  EXPECT_EQ(html.find("Plots are missing"), std::string::npos) << html.substr(0, 3000);
  // Plots (frame time, the peripheral's time per ray, utilisation, latency, wall time), then
  // the three thumbnails: each a real PNG inline.
  const auto images = image_data(html);
  ASSERT_EQ(images.size(), 5u + 3u) << html.substr(0, 3000);
  for (std::size_t i = 0; i < images.size(); ++i) {
    EXPECT_EQ(images[i].rfind("iVBORw0KGgo", 0), 0u) << i;  // base64 of the PNG signature
    EXPECT_GT(images[i].size(), i < 5 ? 5000u : 100u) << i;
  }
  EXPECT_NE(html.find("alt=\"Simulated frame time against peripheral.grid.divisions\""),
            std::string::npos);
  EXPECT_NE(html.find("alt=\"peripheral.time_per_ray_s against"), std::string::npos);
  EXPECT_NE(html.find("alt=\"point 0002\""), std::string::npos);
  EXPECT_NE(html.find("Every point&#39;s image (3)"), std::string::npos);
  // --baseline 1: every point against point 0001 (bold), as rtsim diff compares two runs.
  EXPECT_NE(html.find("<h2>Against the baseline: point 0001</h2>"), std::string::npos);
  EXPECT_NE(html.find("<tr class=\"set\"><td>0001</td><td>peripheral.grid.divisions=4</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td>0%</td><td>1.00</td>"), std::string::npos);
  // shade.max_depth = 0 leaves the ambient term alone: a dark image, shown brighter and said so.
  EXPECT_EQ(count(html, "filter:brightness("), 3);
  EXPECT_NE(html.find("0002: peripheral.grid.divisions=8 (dark: shown"), std::string::npos);
  // How to draw a plot again: a command a shell runs as it is (quotes inside quoted).
  EXPECT_NE(html.find("/usr/bin/python3 analysis/sweep_plot.py results.jsonl plot.png --x"),
            std::string::npos);
  EXPECT_NE(html.find("the point&#39;\\&#39;&#39;s rtsim run"), std::string::npos);
  EXPECT_EQ(count(html, "src=\"http"), 0);
  // Parameters with their sources: the swept one, the fixed one with its line in the sweep file.
  EXPECT_NE(html.find("<tr class=\"set\"><td>peripheral.grid.divisions</td><td>swept: 2, 4, 8"),
            std::string::npos);
  EXPECT_NE(html.find("<td>shade.max_depth</td><td>0</td><td>"), std::string::npos);
  EXPECT_NE(html.find("<td>grid.toml:7</td>"), std::string::npos);
  EXPECT_NE(html.find("Ullner 1983, line"), std::string::npos);
  // The sweep file's text and the headline.
  EXPECT_NE(html.find("name = &quot;tiny-grid&quot;"), std::string::npos);
  EXPECT_NE(html.find("3: 3 ok, 0 failed; 3 run now, 0 done before"), std::string::npos);
  // Staged: no scratch or partial file left behind.
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_EQ(e.path().filename().string().rfind(".rtsim-partial", 0), std::string::npos)
        << e.path();
}

TEST_F(SweepReport, OpensInHeadlessChromiumWithEveryPictureAndNoConsoleMessage) {
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "chromium is not installed (Debian package chromium)";
  if (!matplotlib_available()) GTEST_SKIP() << "no /usr/bin/python3 with matplotlib";
  ASSERT_EQ(result_->exit_code, 0) << result_->output;
  const auto view = open_headless(browser, *dir_ / "out" / "report.html", *dir_);
  ASSERT_EQ(view.exit_code, 0) << view.console;
  const std::string& html = view.dom;
  ASSERT_EQ(image_data(html).size(), 8u) << html.substr(0, 2000);
  // Set by the page once loaded: every <img> decoded (naturalWidth > 0).
  EXPECT_NE(html.find("data-images-decoded=\"8\""), std::string::npos) << html.substr(0, 500);
  EXPECT_EQ(view.console.find(":CONSOLE"), std::string::npos) << view.console;
}

TEST(SweepReportFailures, FailedPointIsListedAndResumingCoversEveryPoint) {
  const fs::path dir = scratch_dir("sweep-report-fail");
  fs::create_directories(dir);
  std::ofstream(dir / "fail.toml") << kFailingSweep;
  // Without Python: the page says why there are no plots (and the test stays fast).
  const std::string cmd = "RTSIM_PYTHON=/nonexistent/python3 " + std::string(RTSIM_BINARY) +
                          " sweep " + (dir / "fail.toml").string() + " --report -q --out " +
                          (dir / "out").string() + " 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1);  // a point failed
  std::string html = read_file(dir / "out" / "report.html");
  EXPECT_NE(html.find("Failed points"), std::string::npos);
  EXPECT_NE(html.find("<tr class=\"set\"><td>0001</td><td>2</td><td>failed</td>"),
            std::string::npos)
      << html.substr(0, 3000);
  EXPECT_NE(html.find("<tr><td>0000</td><td>1</td><td>ok</td>"), std::string::npos);
  EXPECT_NE(html.find("adder_stages"), std::string::npos);
  EXPECT_NE(html.find("Plots are missing"), std::string::npos);
  EXPECT_NE(html.find("/nonexistent/python3"), std::string::npos);
  EXPECT_EQ(image_data(html).size(), 1u);  // the one image of the point that ran
  EXPECT_NE(html.find("2: 1 ok, 1 failed; 2 run now, 0 done before"), std::string::npos);

  // Resumed: the report still covers both points (the failed one runs again).
  fs::remove(dir / "out" / "report.html");
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1);
  html = read_file(dir / "out" / "report.html");
  EXPECT_NE(html.find("2: 1 ok, 1 failed; 1 run now, 1 done before"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>0000</td><td>1</td><td>ok</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>0001</td><td>2</td><td>failed</td>"), std::string::npos);
  fs::remove_all(dir);
}

TEST(SweepReportMpi, RankZeroWritesTheReportOverEveryPoint) {
#ifndef RTSIM_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  const fs::path dir = scratch_dir("sweep-report-mpi");
  fs::create_directories(dir);
  std::ofstream(dir / "fail.toml") << kFailingSweep;
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  const std::string cmd = "RTSIM_PYTHON=/nonexistent/python3 " + std::string(RTSIM_MPIEXEC) +
                          " -np 2 --oversubscribe " + RTSIM_BINARY + " sweep " +
                          (dir / "fail.toml").string() +
                          " --mpi --one-host mpi --report -q --out " + (dir / "out").string() +
                          " >" + (dir / "log").string() + " 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1) << read_file(dir / "log");
  const std::string html = read_file(dir / "out" / "report.html");
  EXPECT_NE(html.find("2 MPI ranks"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>0000</td><td>1</td><td>ok</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>0001</td><td>2</td><td>failed</td>"), std::string::npos);
  EXPECT_EQ(image_data(html).size(), 1u);
  fs::remove_all(dir);
#endif
}
