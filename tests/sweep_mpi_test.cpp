// `rtsim sweep --mpi` under `mpirun -np 2 --oversubscribe` on loopback, over MPI (`--one-host
// mpi`): the table equals the local run's table except the wall-clock columns (failed points
// included), and a bad sweep file stops every rank with status 2 before anything is written;
// `rtsim validate --mpi` likewise gives the local validation. By default (`--one-host jobs`) the
// ranks, all on this host, run the sweep as local jobs in rank 0: the same table, and status 2
// for a bad file. Skipped in a build without MPI.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "platform/sweep/results_table.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::read_jsonl;
using rtsim::test::scratch_dir;

namespace {

using Json = nlohmann::ordered_json;

#ifdef RTSIM_MPIEXEC
rtsim::test::CommandResult run_mpi(const std::string& args) {
  // OpenMPI refuses to run as root (CI containers) unless told twice.
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  return rtsim::test::run_shell(std::string(RTSIM_MPIEXEC) + " -np 2 --oversubscribe " +
                                RTSIM_BINARY + " " + args);
}
#endif

// The table without its wall-clock cells.
std::vector<Json> without_wall_clock(std::vector<Json> rows) {
  for (auto& r : rows)
    for (auto& [key, value] : r.items())
      if (rtsim::sweep::is_wall_clock_column(key)) value = nullptr;
  return rows;
}

}  // namespace

TEST(SweepMpi, TwoRanksGiveTheLocalTable) {
#ifndef RTSIM_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  const fs::path dir = scratch_dir("sweep-mpi");
  fs::create_directories(dir);
  const fs::path file = dir / "tiny.toml";
  std::ofstream(file) << "machine = \"ullner-peripheral\"\n"
                         "scene = \"builtin:ullner-sheets-1000\"\n"
                         "width = 16\nheight = 12\n"
                         "[params]\n\"shade.max_depth\" = 0\n"
                         "[[axes]]\nparam = \"peripheral.grid.divisions\"\nvalues = [0, 3, 6]\n"
                         "[[axes]]\nparam = \"peripheral.adder_stages\"\nvalues = [1, 2]\n";
  const auto local = rtsim::test::run_rtsim("sweep " + file.string() + " --jobs 2 --out " +
                                            (dir / "local").string());
  EXPECT_EQ(local.exit_code, 1) << local.output;  // adder_stages = 2 fails on three points
  const auto mpi =
      run_mpi("sweep " + file.string() + " --mpi --one-host mpi --out " + (dir / "mpi").string());
  EXPECT_EQ(mpi.exit_code, 1) << mpi.output;
  EXPECT_NE(mpi.output.find("6 points, 6 to run (0 done before), 2 MPI ranks"), std::string::npos)
      << mpi.output;

  const auto local_rows = read_jsonl(dir / "local" / "results.jsonl");
  const auto mpi_rows = read_jsonl(dir / "mpi" / "results.jsonl");
  ASSERT_EQ(local_rows.size(), 6u);
  EXPECT_EQ(without_wall_clock(mpi_rows), without_wall_clock(local_rows));
  std::size_t failed = 0;
  for (const auto& r : mpi_rows) failed += r["status"] == "failed" ? 1 : 0;
  EXPECT_EQ(failed, 3u);
  // Same columns in the CSV.
  const std::string a = read_file(dir / "local" / "results.csv");
  const std::string b = read_file(dir / "mpi" / "results.csv");
  EXPECT_EQ(a.substr(0, a.find('\n')), b.substr(0, b.find('\n')));
  for (const char* key : {"0000", "0002", "0004"})
    EXPECT_TRUE(fs::exists(dir / "mpi" / "points" / key / "done.json")) << key;

  // Resuming works under MPI too: nothing left to run but the failed points.
  const auto again =
      run_mpi("sweep " + file.string() + " --mpi --one-host mpi --out " + (dir / "mpi").string());
  EXPECT_NE(again.output.find("6 points, 3 to run (3 done before)"), std::string::npos)
      << again.output;
  fs::remove_all(dir);
#endif
}

TEST(SweepMpi, BadSweepStopsEveryRankWithStatus2) {
#ifndef RTSIM_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  const fs::path dir = scratch_dir("sweep-mpi-bad");
  fs::create_directories(dir);
  const fs::path file = dir / "bad.toml";
  std::ofstream(file) << "machine = \"ullner-peripheral\"\nscene = \"builtin:default\"\n"
                         "[params]\n\"peripheral.grid.divisons\" = 3\n";
  for (const char* one_host : {"mpi", "jobs"}) {
    const auto r = run_mpi("sweep " + file.string() + " --mpi --one-host " + one_host + " --out " +
                           (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << one_host << "\n" << r.output;
    EXPECT_NE(r.output.find(":4: on machine 'ullner-peripheral': unknown parameter"),
              std::string::npos)
        << one_host << "\n"
        << r.output;
    EXPECT_FALSE(fs::exists(dir / "out")) << one_host;
  }
  fs::remove_all(dir);
#endif
}

TEST(SweepMpi, RanksOnOneHostRunTheSweepAsLocalJobs) {
#ifndef RTSIM_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  const fs::path dir = scratch_dir("sweep-mpi-one-host");
  fs::create_directories(dir);
  const fs::path file = dir / "tiny.toml";
  std::ofstream(file) << "machine = \"ullner-peripheral\"\n"
                         "scene = \"builtin:ullner-sheets-1000\"\n"
                         "width = 16\nheight = 12\n"
                         "[[axes]]\nparam = \"peripheral.grid.divisions\"\nvalues = [0, 3, 6]\n";
  const auto local = rtsim::test::run_rtsim("sweep " + file.string() + " --jobs 2 --out " +
                                            (dir / "local").string());
  ASSERT_EQ(local.exit_code, 0) << local.output;
  const auto one_host =
      run_mpi("sweep " + file.string() + " --mpi --out " + (dir / "one-host").string());
  ASSERT_EQ(one_host.exit_code, 0) << one_host.output;
  // Said once (rank 1 leaves at once), with every rank's slots: 2 jobs.
  const std::string said =
      "all 2 MPI ranks are on this host: rank 0 runs the points as 2 local "
      "jobs";
  EXPECT_NE(one_host.output.find(said), std::string::npos) << one_host.output;
  EXPECT_EQ(one_host.output.find(said), one_host.output.rfind(said)) << one_host.output;
  EXPECT_NE(one_host.output.find("3 points, 3 to run (0 done before), 2 at a time"),
            std::string::npos)
      << one_host.output;
  EXPECT_EQ(without_wall_clock(read_jsonl(dir / "one-host" / "results.jsonl")),
            without_wall_clock(read_jsonl(dir / "local" / "results.jsonl")));
  // --one-host is an option of --mpi.
  const auto alone = rtsim::test::run_rtsim("sweep " + file.string() + " --one-host mpi");
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
  EXPECT_NE(alone.output.find("--one-host requires --mpi"), std::string::npos) << alone.output;
  fs::remove_all(dir);
#endif
}

// `rtsim validate --sensitivity --mpi`: the figures' runs and the moved ones spread over the
// ranks give the rows and the sensitivity of a local run (wall times apart).
TEST(ValidateMpi, TwoRanksGiveTheLocalValidationAndSensitivity) {
#ifndef RTSIM_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  const fs::path dir = scratch_dir("validate-mpi");
  const std::string args = "validate --quick --sensitivity --only X4b,W1h --jobs 1 --out ";
  const auto local = rtsim::test::run_rtsim(args + (dir / "local").string());
  ASSERT_EQ(local.exit_code, 0) << local.output;
  const auto mpi = run_mpi(args + (dir / "mpi").string() + " --mpi --one-host mpi");
  ASSERT_EQ(mpi.exit_code, 0) << mpi.output;
  EXPECT_NE(mpi.output.find("on each of 2 MPI ranks"), std::string::npos) << mpi.output;
  // By default the two ranks, on this host, validate as local jobs in rank 0.
  const auto one_host = run_mpi(args + (dir / "one-host").string() + " --mpi");
  ASSERT_EQ(one_host.exit_code, 0) << one_host.output;
  EXPECT_NE(one_host.output.find("all 2 MPI ranks are on this host: rank 0 runs the runs as 2 "
                                 "local jobs"),
            std::string::npos)
      << one_host.output;
  for (const char* run : {"mpi", "one-host"})
    for (const char* file : {"validation.json", "validation-sensitivity.json"}) {
      auto a = Json::parse(read_file(dir / "local" / file));
      auto b = Json::parse(read_file(dir / run / file));
      EXPECT_EQ(a["rows"], b["rows"]) << run << " " << file;
      EXPECT_EQ(a["entries"], b["entries"]) << run << " " << file;
      EXPECT_EQ(a["verdict_depends"], b["verdict_depends"]) << run << " " << file;
    }
  const auto s = Json::parse(read_file(dir / "mpi" / "validation-sensitivity.json"));
  ASSERT_EQ(s["verdict_depends"].size(), 1u);
  EXPECT_EQ(s["verdict_depends"][0]["figure"], "X4b");
  // A bad --only stops every rank with status 2, over MPI or not.
  for (const char* one_host : {"mpi", "jobs"}) {
    const auto bad = run_mpi("validate --quick --only NOPE --mpi --one-host " +
                             std::string(one_host) + " --out " + (dir / "bad").string());
    EXPECT_EQ(bad.exit_code, 2) << one_host << "\n" << bad.output;
  }
  fs::remove_all(dir);
#endif
}
