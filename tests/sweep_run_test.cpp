// `rtsim sweep` end to end on tiny images (16x12): the rows and their values against each
// point's own stats.json and the brute-force count, a failing point recorded without stopping
// the others (exit status 1), a point killed by a signal, resuming (a second run runs nothing;
// changing one value re-runs only the points that changed), --force and --list.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "platform/machine_registry.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::read_jsonl;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

using Json = nlohmann::ordered_json;

// builtin:ullner-sheets-1000 holds 968 quadrilaterals (two sheets cut to the modelling space).
constexpr int kSheetQuads = 968;
constexpr int kRays = 16 * 12;  // primary rays only (shade.max_depth = 0)

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// A sweep of the peripheral (the default machine: the registry names it, not this test): grid
// divisions x adder stages. adder_stages = 2 is within the
// parameter's declared bounds (1..3), so the sweep passes its checks, but the machine accepts
// only 1 or 3 (Fig. 2-17): those points fail at run time, as a real what-if sweep may.
const std::string& peripheral() { return rtsim::platform::default_machine().name(); }

std::string peripheral_sweep(const std::string& divisions) {
  return "name = \"tiny\"\nmachine = \"" + peripheral() +
         "\"\n"
         "scene = \"builtin:ullner-sheets-1000\"\n"
         "width = 16\n"
         "height = 12\n"
         "[params]\n"
         "\"shade.max_depth\" = 0\n"
         "[[axes]]\n"
         "param = \"peripheral.grid.divisions\"\n"
         "values = [" +
         divisions +
         "]\n"
         "[[axes]]\n"
         "param = \"peripheral.adder_stages\"\n"
         "values = [1, 2]\n";
}

std::int64_t mtime_ns(const fs::path& p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return -1;
  return static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec;
}

}  // namespace

TEST(SweepRun, RowsFailuresAndResuming) {
  const fs::path dir = scratch_dir("sweep-run");
  fs::create_directories(dir);
  const fs::path file = dir / "tiny.toml";
  const fs::path out = dir / "out";
  write(file, peripheral_sweep("0, 4"));

  // --list shows the four command lines and runs nothing. Points 1 and 3 differ from 0 and 2
  // only in a parameter the image does not depend on: they run timing-only (--image none).
  const auto listed = run_rtsim("sweep " + file.string() + " --list --out " + out.string());
  EXPECT_EQ(listed.exit_code, 0) << listed.output;
  EXPECT_NE(listed.output.find("0003        rtsim run --machine " + peripheral() +
                               " --scene "
                               "builtin:ullner-sheets-1000 --width 16 --height 12 --image none "
                               "-q -p shade.max_depth=0 -p peripheral.grid.divisions=4 -p "
                               "peripheral.adder_stages=2"),
            std::string::npos)
      << listed.output;
  EXPECT_FALSE(fs::exists(out));

  const auto first = run_rtsim("sweep " + file.string() + " --jobs 2 --out " + out.string());
  EXPECT_EQ(first.exit_code, 1) << first.output;  // two points failed
  EXPECT_NE(first.output.find("4 points, 4 to run (0 done before)"), std::string::npos)
      << first.output;
  const auto rows = read_jsonl(out / "results.jsonl");
  ASSERT_EQ(rows.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const Json& r = rows[i];
    const int divisions = i < 2 ? 0 : 4;
    const int adders = i % 2 == 0 ? 1 : 2;
    SCOPED_TRACE("point " + std::to_string(i));
    EXPECT_EQ(r["point"], i);  // point order, not completion order
    EXPECT_EQ(r["machine"], peripheral());
    EXPECT_EQ(r["scene"], "builtin:ullner-sheets-1000");
    EXPECT_EQ(r["peripheral.grid.divisions"], divisions);
    EXPECT_EQ(r["peripheral.adder_stages"], adders);
    EXPECT_EQ(r["width"], 16);
    EXPECT_EQ(r["height"], 12);
    EXPECT_GT(r["point_wall_time_s"].get<double>(), 0.0);
    const fs::path point_dir = out / r["dir"].get<std::string>();
    if (adders == 2) {
      EXPECT_EQ(r["status"], "failed");
      EXPECT_EQ(r["exit_code"], 2);
      EXPECT_NE(r["error"].get<std::string>().find("exit status 2: rtsim: error: "),
                std::string::npos);
      EXPECT_NE(r["error"].get<std::string>().find("must be 1 or 3"), std::string::npos);
      EXPECT_TRUE(r["simulated_time_s"].is_null());
      EXPECT_FALSE(fs::exists(point_dir / "done.json"));
      EXPECT_TRUE(fs::exists(point_dir / "run.log"));
      continue;
    }
    EXPECT_EQ(r["status"], "ok");
    EXPECT_EQ(r["exit_code"], 0);
    EXPECT_EQ(r["error"], "");
    EXPECT_EQ(r["rays.primary"], kRays);
    // The row holds the point's own stats.json values.
    const Json stats = Json::parse(read_file(point_dir / "stats.json"));
    EXPECT_EQ(r["simulated_time_s"], stats["simulated_time_s"]);
    EXPECT_EQ(r["intersection_tests"], stats["intersection_tests"]);
    EXPECT_EQ(r["modules.peripheral.pipeline.utilization"],
              stats["modules"]["peripheral.pipeline"]["utilization"]);
    EXPECT_EQ(r["peripheral.grid_divisions"], divisions);
    EXPECT_GT(r["simulated_time_s"].get<double>(), 0.0);
    EXPECT_TRUE(fs::exists(point_dir / "done.json"));
  }
  // Brute force tests every quad with every ray; the grid tests fewer and takes less time.
  EXPECT_EQ(rows[0]["intersection_tests"], kRays * kSheetQuads);
  EXPECT_LT(rows[2]["intersection_tests"].get<long>(), kRays * kSheetQuads);
  EXPECT_LT(rows[2]["simulated_time_s"].get<double>(), rows[0]["simulated_time_s"].get<double>());

  // The CSV has the same rows and columns.
  const std::string csv = read_file(out / "results.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_TRUE(
      csv.starts_with("point,machine,scene,width,height,peripheral.grid.divisions,"
                      "peripheral.adder_stages,status,exit_code,error,point_wall_time_s,"
                      "dir,simulated_time_s,wall_time_s,rays.total,"))
      << csv.substr(0, 300);

  // Second run: the done points are skipped (their files untouched); the failed ones run again.
  const auto stamp0 = mtime_ns(out / "points/0000/stats.json");
  const auto second = run_rtsim("sweep " + file.string() + " --jobs 2 --out " + out.string());
  EXPECT_EQ(second.exit_code, 1);
  EXPECT_NE(second.output.find("4 points, 2 to run (2 done before)"), std::string::npos)
      << second.output;
  EXPECT_EQ(mtime_ns(out / "points/0000/stats.json"), stamp0);
  const auto rows2 = read_jsonl(out / "results.jsonl");
  ASSERT_EQ(rows2.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    for (const auto& [key, value] : rows[i].items()) {
      // A reused point keeps its wall time; a failed one ran again.
      if (key == "point_wall_time_s" && i % 2 == 1) continue;
      EXPECT_EQ(rows2[i][key], value) << i << " " << key;
    }
  }

  // Change one value (divisions 4 -> 5): only the point of it that can succeed runs again, plus
  // the failing ones; point 0 keeps its files.
  write(file, peripheral_sweep("0, 5"));
  const auto third = run_rtsim("sweep " + file.string() + " --jobs 2 --out " + out.string());
  EXPECT_EQ(third.exit_code, 1);
  EXPECT_NE(third.output.find("4 points, 3 to run (1 done before)"), std::string::npos)
      << third.output;
  EXPECT_EQ(mtime_ns(out / "points/0000/stats.json"), stamp0);
  const auto rows3 = read_jsonl(out / "results.jsonl");
  ASSERT_EQ(rows3.size(), 4u);
  EXPECT_EQ(rows3[2]["peripheral.grid.divisions"], 5);
  EXPECT_EQ(rows3[2]["peripheral.grid_divisions"], 5);  // from the re-run point's stats.json
  EXPECT_EQ(rows3[2]["status"], "ok");

  // --force runs them all.
  const auto forced =
      run_rtsim("sweep " + file.string() + " --force -q --jobs 2 --out " + out.string());
  EXPECT_EQ(forced.exit_code, 1);
  EXPECT_NE(mtime_ns(out / "points/0000/stats.json"), stamp0);
  fs::remove_all(dir);
}

TEST(SweepRun, ScenesAsAnAxisAndAPointKilledBySignal) {
  const fs::path dir = scratch_dir("sweep-crash");
  fs::create_directories(dir);
  // A stand-in for rtsim that crashes on one point and runs the real binary otherwise: a
  // crash stays in its own process, and the sweep goes on.
  const fs::path wrapper = dir / "rtsim-crashing";
  write(wrapper, std::string("#!/bin/sh\ncase \"$*\" in *shade.max_depth=1*) kill -SEGV $$ ;; "
                             "esac\nexec ") +
                     RTSIM_BINARY + " \"$@\"\n");
  fs::permissions(wrapper, fs::perms::owner_all);
  const fs::path file = dir / "vax.toml";
  // A scene file relative to the sweep file's folder, and a builtin scene.
  fs::copy_file(rtsim::test::shared_path("scenes/tetra-s3.nff"), dir / "tetra.nff");
  write(file,
        "machine = \"vax-750\"\n"
        "scenes = [\"tetra.nff\", \"builtin:ullner-cubes\"]\n"
        "width = 16\nheight = 12\n"
        "[[axes]]\nparam = \"shade.max_depth\"\nvalues = [0, 1]\n");
  const fs::path out = dir / "out";
  const auto r = run_rtsim("sweep " + file.string() + " --jobs 2 --rtsim " + wrapper.string() +
                           " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto rows = read_jsonl(out / "results.jsonl");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0]["scene"], "tetra.nff");
  EXPECT_EQ(rows[2]["scene"], "builtin:ullner-cubes");
  for (int i : {1, 3}) {
    EXPECT_EQ(rows[i]["status"], "failed");
    EXPECT_EQ(rows[i]["exit_code"], -1);
    EXPECT_TRUE(rows[i]["error"].get<std::string>().starts_with("killed by signal"))
        << rows[i]["error"];
  }
  for (int i : {0, 2}) {
    EXPECT_EQ(rows[i]["status"], "ok") << rows[i]["error"];
    // On the VAX every ray tests every object (seed 001 L326).
    EXPECT_EQ(rows[i]["intersection_tests"].get<long>(),
              rows[i]["rays.total"].get<long>() * rows[i]["vax.objects"].get<long>());
  }
  EXPECT_NE(rows[0]["vax.objects"], rows[2]["vax.objects"]);
  fs::remove_all(dir);
}

TEST(SweepRun, ALargeArrayIsColumnsOfItsClassesAndItsInstancesAreInModulesCsv) {
  // A 16 x 16 array as instances was 19,279 columns (more than a spreadsheet holds); its
  // classes (node*, node*.link_e, ...) are a few hundred, at every size the sweep visits.
  const fs::path dir = scratch_dir("sweep-array-classes");
  fs::create_directories(dir);
  const fs::path file = dir / "sizes.toml";
  const fs::path out = dir / "out";
  write(file,
        "machine = \"ullner-array\"\nscene = \"builtin:ullner-cubes\"\nwidth = 32\nheight = 32\n"
        "[[axes]]\nzip = [\n  { param = \"array.rows\", values = [4, 16] },\n"
        "  { param = \"array.cols\", values = [4, 16] },\n]\n");
  const auto r = run_rtsim("sweep " + file.string() + " -q --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream csv(out / "results.csv");
  std::string header;
  std::getline(csv, header);
  std::vector<std::string> columns;
  std::stringstream cells(header);
  for (std::string c; std::getline(cells, c, ',');) columns.push_back(c);
  std::printf("results.csv of a 4 x 4 and a 16 x 16 array: %zu columns (limit 300)\n",
              columns.size());
  EXPECT_LT(columns.size(), 300u);
  for (const auto& c : columns) EXPECT_NE(c.rfind("modules.node", 0), 0u) << c;
  for (const char* c :
       {"module_classes.node*.utilization.mean", "module_classes.node*.utilization.max_instance",
        "module_classes.node*.in_e.queue.mean_occupancy.max",
        "module_classes.node*.sent_vision.mean", "module_classes.node*.instances"})
    EXPECT_NE(std::find(columns.begin(), columns.end(), c), columns.end()) << c;

  // Every instance is in the point's modules.csv: 256 nodes, each with its links, queues,
  // memory and unit.
  std::ifstream modules(out / "points" / "0001" / "modules.csv");
  ASSERT_TRUE(modules) << "no modules.csv";
  std::string line;
  std::getline(modules, line);
  EXPECT_EQ(line.rfind("module,class,", 0), 0u) << line;
  int nodes = 0;
  while (std::getline(modules, line))
    if (line.find(",node*,") != std::string::npos) ++nodes;
  EXPECT_EQ(nodes, 256);
}
