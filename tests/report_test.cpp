// `rtsim run --report`: report.html is one self-contained page (pictures embedded as base64
// PNG), staged with the other outputs, with plots drawn by analysis/ when Debian's python3 and
// matplotlib are there and a note instead when they are not; and it opens in headless
// Chromium (Debian's chromium package) with every picture decoded and no console message. A run
// with --latency-probe gains the "Where a ray spends its time" table and plot.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <regex>

#include "app/number_text.hpp"
#include "app/run_report.hpp"
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

namespace {

const char* kRunArgs =
    "run --machine ullner-peripheral --scene builtin:ullner-cubes --width 32 --height 32 "
    "-p peripheral.grid.divisions=4 --trace perfetto --latency-probe --report -q";

/// The <table> that follows `heading` (an <h2>), or "" if there is none.
std::string table_after(const std::string& html, const std::string& heading) {
  const std::size_t h = html.find("<h2>" + heading + "</h2>");
  if (h == std::string::npos) return "";
  const std::size_t t = html.find("<table>", h);
  const std::size_t next = html.find("<h2>", h + 4);
  if (t == std::string::npos || t > next) return "";
  return html.substr(t, html.find("</table>", t) - t);
}

}  // namespace

TEST(Report, Base64AndEscaping) {
  EXPECT_EQ(rtsim::app::base64(""), "");
  EXPECT_EQ(rtsim::app::base64("f"), "Zg==");
  EXPECT_EQ(rtsim::app::base64("fo"), "Zm8=");
  EXPECT_EQ(rtsim::app::base64("foo"), "Zm9v");
  EXPECT_EQ(rtsim::app::base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(rtsim::app::base64(std::string("\x89PNG", 4)), "iVBORw==");
  EXPECT_EQ(rtsim::app::html_escape("<a href=\"x\">&'</a>"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
}

TEST(Report, RunWritesASelfContainedPageWithImagePlotsAndParameters) {
  if (!matplotlib_available()) GTEST_SKIP() << "no /usr/bin/python3 with matplotlib";
  const auto dir = scratch_dir("report");
  const auto r = run_rtsim(std::string(kRunArgs) + " --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(dir / "report.html"));
  const std::string html = read_file(dir / "report.html");
  // The frame, the utilisation timeline, the latency histogram and the latency breakdown, each
  // a real PNG inline.
  const auto images = image_data(html);
  ASSERT_EQ(images.size(), 4u) << html.substr(0, 2000);
  for (const auto& b64 : images) {
    EXPECT_EQ(b64.rfind("iVBORw0KGgo", 0), 0u);  // base64 of the PNG signature
    EXPECT_GT(b64.size(), 1000u);
  }
  EXPECT_EQ(count(html, "src=\"http"), 0);  // nothing fetched from elsewhere
  EXPECT_EQ(count(html, "src=\"file"), 0);
  EXPECT_NE(html.find("simulated frame time"), std::string::npos);
  EXPECT_NE(html.find("ray latency"), std::string::npos);
  EXPECT_NE(html.find("peripheral.pipeline"), std::string::npos);
  // --latency-probe: the breakdown table, stages as a ray meets them, then its plot.
  const std::string probe = table_after(html, "Where a ray spends its time");
  ASSERT_FALSE(probe.empty()) << "no latency breakdown table";
  EXPECT_NE(probe.find("<th>queueing</th><th>service</th><th>transfer</th><th>total</th>"
                       "<th>share</th>"),
            std::string::npos)
      << probe;
  std::size_t last = 0;
  for (const char* stage : {"peripheral.ray_queue", "peripheral.aux", "peripheral.pipeline",
                            "host.result_queue", "unattributed", "end to end (mean)"}) {
    const std::size_t at = probe.find("<tr><td>" + std::string(stage) + "</td>");
    ASSERT_NE(at, std::string::npos) << stage << " in " << probe;
    EXPECT_GT(at, last) << stage << " out of order";
    last = at;
  }
  EXPECT_NE(probe.find("0 (rounding"), std::string::npos) << probe;  // nothing unattributed
  const std::size_t plot = html.find("alt=\"where a ray spends its time\"");
  EXPECT_NE(plot, std::string::npos);
  EXPECT_GT(plot, html.find("<h2>Where a ray spends its time</h2>"));
  // Parameters with where they were set and their documented source.
  EXPECT_NE(html.find("<tr class=\"set\"><td>peripheral.grid.divisions</td><td>4</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td>-p</td>"), std::string::npos);
  EXPECT_NE(html.find("Ullner 1983, line"), std::string::npos);
  EXPECT_EQ(html.find("Plots are missing"), std::string::npos);
  // Staged with the rest: no scratch or partial file left behind.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().rfind(".rtsim-partial", 0), std::string::npos)
        << e.path();
  fs::remove_all(dir);
}

TEST(Report, AMachinesOwnFiguresAreTablesNotRawJson) {
  // gaudet-pert's `gaudet` object: its three processors side by side, its buses in a table.
  const auto dir = scratch_dir("report-gaudet");
  const auto r = run_rtsim(
      "run --machine gaudet-pert --scene builtin:npp-412 --width 24 --height 24 -p pert_count=2 "
      "--report -q --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string html = read_file(dir / "report.html");
  const auto section = html.find("<h2>gaudet</h2>");
  ASSERT_NE(section, std::string::npos);
  const std::string g = html.substr(section, html.find("<h2>", section + 1) - section);
  // The processors in pipeline order, their time split a row each, in engineering units.
  EXPECT_NE(g.find("<tr><th></th><th>shade</th><th>shell</th><th>prim</th></tr>"),
            std::string::npos)
      << g.substr(0, 2000);
  EXPECT_NE(g.find("<tr><td>processing_per_ray_s</td><td>"), std::string::npos);
  EXPECT_NE(g.find(" µs</td>"), std::string::npos);
  EXPECT_NE(g.find("gaudet.buses:"), std::string::npos);
  EXPECT_NE(g.find("<tr><td>utilization</td><td>"), std::string::npos);
  // No object shown as JSON text.
  EXPECT_EQ(g.find("{&quot;"), std::string::npos) << g.substr(0, 2000);
  EXPECT_EQ(g.find("...</td>"), std::string::npos);
}

TEST(Report, AClassOfManyInstancesIsOneRowOfItsAggregates) {
  // A 16 x 16 array: 256 nodes, each with its links, queues, memory and unit, are a row a class,
  // not 2,688 rows.
  const auto dir = scratch_dir("report-array-classes");
  const auto r = run_rtsim(
      "run --machine ullner-array --scene builtin:ullner-cubes -p array.rows=16 "
      "-p array.cols=16 --width 32 --height 32 -q --report --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string page = read_file(dir / "report.html");
  for (const char* s : {"node* (256 instances)", "node*.link_e (240 instances)", "module_classes"})
    EXPECT_NE(page.find(s), std::string::npos) << s;
  EXPECT_EQ(page.find(">node17<"), std::string::npos);
  EXPECT_EQ(page.find(">node17.memory<"), std::string::npos);
  // And the processes' activations: one row, not 256 (stats.json keeps them all).
  EXPECT_NE(page.find(">node*.activate (256 processes)<"), std::string::npos);
  EXPECT_EQ(page.find(">node17.activate<"), std::string::npos);
}

TEST(Report, BadInputWritesNothing) {
  const auto dir = scratch_dir("report-bad");
  const auto r = run_rtsim("run --scene builtin:no-such-scene --report -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

TEST(Report, WithoutPythonThePageSaysWhyThereAreNoPlots) {
  const auto dir = scratch_dir("report-nopython");
  const std::string cmd = "RTSIM_PYTHON=/nonexistent/python3 " + std::string(RTSIM_BINARY) +
                          " run --machine vax-750 --scene builtin:ullner-cubes --width 8 "
                          "--height 8 -p shade.max_depth=0 --report -q --out " +
                          dir.string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string html = read_file(dir / "report.html");
  EXPECT_EQ(image_data(html).size(), 1u);  // the frame only
  EXPECT_NE(html.find("Plots are missing"), std::string::npos);
  EXPECT_NE(html.find("/nonexistent/python3"), std::string::npos);
  EXPECT_NE(html.find("simulated frame time"), std::string::npos);
  EXPECT_EQ(html.find("Where a ray spends its time"), std::string::npos);  // no --latency-probe
  fs::remove_all(dir);
  // With the probe the table needs no Python; only its plot is missing, with a note.
  ASSERT_EQ(std::system((cmd.substr(0, cmd.find(" --report")) + " --latency-probe" +
                         cmd.substr(cmd.find(" --report")))
                            .c_str()),
            0);
  const std::string probed = read_file(dir / "report.html");
  EXPECT_EQ(image_data(probed).size(), 1u);
  EXPECT_NE(table_after(probed, "Where a ray spends its time").find("<tr><td>vax</td>"),
            std::string::npos);
  const std::size_t section = probed.find("<h2>Where a ray spends its time</h2>");
  ASSERT_NE(section, std::string::npos);
  EXPECT_NE(probed.find("Plots are missing", section), std::string::npos);
  fs::remove_all(dir);
}

TEST(Report, OpensInHeadlessChromiumWithEveryPictureAndNoConsoleMessage) {
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "chromium is not installed (Debian package chromium)";
  if (!matplotlib_available()) GTEST_SKIP() << "no /usr/bin/python3 with matplotlib";
  const auto dir = scratch_dir("report-chromium");
  const auto r = run_rtsim(std::string(kRunArgs) + " --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto view = open_headless(browser, dir / "report.html", dir);
  ASSERT_EQ(view.exit_code, 0) << view.console;
  const std::string& html = view.dom;
  const auto images = image_data(html);
  ASSERT_EQ(images.size(), 4u) << html.substr(0, 2000);
  for (const auto& b64 : images) EXPECT_GT(b64.size(), 1000u);
  // Set by the page once loaded: every <img> decoded (naturalWidth > 0), the latency
  // breakdown's plot among them.
  EXPECT_NE(html.find("data-images-decoded=\"4\""), std::string::npos) << html.substr(0, 500);
  EXPECT_NE(html.find("alt=\"where a ray spends its time\""), std::string::npos);
  // Chromium logs every console message (console.log, console.error, uncaught exceptions) as
  // ":CONSOLE" lines; the page writes to the console only when something is wrong.
  EXPECT_EQ(view.console.find(":CONSOLE"), std::string::npos) << view.console;
  fs::remove_all(dir);
}

// Every machine's report reads as a person reads numbers: no array or object as JSON text, no
// number in e-notation (images aside), on its own sample scene with the machine's sections.
class ReportOfEveryMachine : public testing::TestWithParam<rtsim::test::MachineInfo> {};

TEST_P(ReportOfEveryMachine, NoRawJsonAndNoExponents) {
  const auto& m = GetParam();
  const auto dir = scratch_dir("report-every-" + m.name);
  // Without Python: the plots are not what is checked here.
  const std::string cmd = "RTSIM_PYTHON=/nonexistent/python3 " + std::string(RTSIM_BINARY) +
                          " run --machine " + m.name + " --scene " + m.sample_scene +
                          " --width 16 --height 16 --report -q --out " + dir.string() +
                          " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::string html = read_file(dir / "report.html");
  // Images and plots are base64: cut them out.
  for (std::size_t at; (at = html.find("base64,")) != std::string::npos;)
    html.erase(at, html.find('"', at) - at);
  EXPECT_EQ(html.find("<td>["), std::string::npos) << m.name;
  EXPECT_EQ(html.find("<td>{"), std::string::npos) << m.name;
  EXPECT_EQ(html.find("{&quot;"), std::string::npos) << m.name;
  const std::regex exponent("[0-9]e[-+][0-9]");
  std::smatch hit;
  if (std::regex_search(html, hit, exponent)) {
    const auto at = static_cast<std::size_t>(hit.position(0));
    ADD_FAILURE() << m.name << ": a number in e-notation: ..."
                  << html.substr(at < 120 ? 0 : at - 120, 200) << "...";
  }
  // Every number of stats.json as the console, diff and reports show it (format_figure): no
  // exponent, a rate never as a time, a count never with a unit.
  std::size_t figures = 0;
  rtsim::test::each_number(
      nlohmann::json::parse(read_file(dir / "stats.json")), [&](const std::string& path, double x) {
        ++figures;
        const std::string text = rtsim::app::format_figure(path, x);
        EXPECT_FALSE(std::regex_search(text, std::regex("[0-9]e[-+]?[0-9]")))
            << path << " = " << text;
        if (path.ends_with("_per_s") || path.ends_with(".count")) {
          EXPECT_TRUE(std::regex_match(text, std::regex("-?[0-9]+(\\.[0-9]+)?")))
              << path << " = " << text;
        }
      });
  EXPECT_GT(figures, 50u) << m.name;
  // Opened 1280 px wide, nothing runs off the page (a wide table, a long unbroken word).
  if (const std::string browser = chromium(); !browser.empty()) {
    const auto view = open_headless(browser, dir / "report.html", dir);
    ASSERT_EQ(view.exit_code, 0) << view.console;
    std::smatch width;
    ASSERT_TRUE(std::regex_search(view.dom, width, std::regex("data-page-width=\"([0-9]+)\"")))
        << view.dom.substr(0, 500);
    std::printf("%s: the report is %s px wide in a 1280 px window\n", m.name.c_str(),
                width[1].str().c_str());
    EXPECT_LE(std::stoi(width[1].str()), 1280) << m.name;
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Machines, ReportOfEveryMachine,
                         testing::ValuesIn(rtsim::test::registered_machines()),
                         rtsim::test::machine_param_name);
