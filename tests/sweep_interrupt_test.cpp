// `rtsim sweep` stopped part-way: Ctrl-C writes the table of the points done and says how to
// resume; a second sweep into the same --out is refused while one runs; a sweep killed outright
// takes its points with it.
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/file.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "common/spawn_logged.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

// Twelve points of a few tenths of a second each, one at a time: under MPI, mpirun takes about
// half a second to pass an interrupt on, and the points left must outlast it.
constexpr int kPoints = 12;
fs::path write_slow_sweep(const fs::path& dir) {
  fs::create_directories(dir);
  const fs::path file = dir / "slow.toml";
  std::ofstream(file) << "machine = \"gaudet-pert\"\nscene = \"builtin:npp-412\"\n"
                         "width = 192\nheight = 192\n[[axes]]\nparam = \"pert_count\"\n"
                         "range = { start = 1, stop = 12 }\n";
  return file;
}

/// Starts `rtsim sweep FILE --out OUT ...` in the background; its output goes to `log`. With
/// `programs`, its points are programs started anew (--rtsim), not forks of the sweep.
pid_t start_sweep(const fs::path& file, const fs::path& out, const std::string& jobs,
                  const fs::path& log, bool programs = false) {
  std::vector<std::string> args = {RTSIM_BINARY, "sweep", file.string(), "--jobs",
                                   jobs,         "--out", out.string()};
  if (programs) args.insert(args.end(), {"--rtsim", RTSIM_BINARY});
  std::string error;
  const pid_t pid = rtsim::spawn_logged(args, log, false, error);
  EXPECT_GT(pid, 0) << error;
  return pid;
}

/// Waits until `path` exists (true) or `seconds` pass (false).
bool wait_for(const fs::path& path, int seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (!fs::exists(path)) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

/// Processes whose command line names `needle` (the sweep's own --out: its points are forks
/// with the same command line).
int processes_naming(const std::string& needle) {
  int n = 0;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string cmd = read_file(e.path() / "cmdline");
    std::string flat = cmd;
    for (char& c : flat)
      if (c == '\0') c = ' ';
    if (flat.find(needle) != std::string::npos) ++n;
  }
  return n;
}

int count_of(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// What an interrupted sweep leaves: the message, and a table of every point, the ones done
/// `ok` and the rest `interrupted`. Returns how many are done.
int expect_partial_table(const fs::path& log, const fs::path& out) {
  const std::string said = read_file(log);
  std::cout << said;
  EXPECT_NE(said.find("run the same command to resume"), std::string::npos);
  const std::string table = read_file(out / "results.csv");
  const int ok = count_of(table, ",ok,"), interrupted = count_of(table, ",interrupted,");
  EXPECT_GE(ok, 2);
  EXPECT_GE(interrupted, 1);
  EXPECT_EQ(ok + interrupted, kPoints) << table;
  EXPECT_NE(said.find("interrupted: " + std::to_string(ok) + " of " + std::to_string(kPoints) +
                      " points done"),
            std::string::npos);
  return ok;
}

/// Whether every process naming `out` is gone within 10 s.
bool all_gone(const fs::path& out) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (processes_naming(out.string()) > 0 && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  return processes_naming(out.string()) == 0;
}

}  // namespace

TEST(SweepInterrupt, CtrlCWritesThePartialTableAndTheSameCommandResumes) {
  const fs::path dir = scratch_dir("sweep-interrupt");
  const fs::path file = write_slow_sweep(dir), out = dir / "out", log = dir / "sweep.log";
  const pid_t pid = start_sweep(file, out, "1", log);
  ASSERT_TRUE(wait_for(out / "points" / "0001" / "done.json", 120)) << read_file(log);
  ::kill(pid, SIGINT);
  std::string error;
  const int status = rtsim::wait_for_child(pid, error);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep should end by the signal; log:\n"
                                   << read_file(log);
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  const int ok = expect_partial_table(log, out);
  // No point left partial outputs behind.
  for (const auto& e : fs::recursive_directory_iterator(out))
    EXPECT_EQ(e.path().filename().string().find(".rtsim-partial-"), std::string::npos) << e.path();
  // The same command runs only what is left.
  const auto again = run_rtsim("sweep " + file.string() + " --jobs 2 --out " + out.string());
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find(std::to_string(kPoints - ok) + " to run (" + std::to_string(ok) +
                              " done before)"),
            std::string::npos)
      << again.output;
  EXPECT_EQ(count_of(read_file(out / "results.csv"), ",ok,"), kPoints);
}

TEST(SweepInterrupt, ASecondSweepIntoTheSameFolderIsRefused) {
  const fs::path dir = scratch_dir("sweep-lock");
  const fs::path file = write_slow_sweep(dir), out = dir / "out";
  fs::create_directories(out);
  // What a running sweep holds: an exclusive flock on the folder's lock file.
  const int fd = ::open((out / ".rtsim-sweep.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const auto r = run_rtsim("sweep " + file.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("another rtsim sweep is writing into this folder"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out / "results.csv"));
  ::close(fd);  // released: the folder is free again
  const auto list = run_rtsim("sweep " + file.string() + " --list --out " + out.string());
  EXPECT_EQ(list.exit_code, 0) << list.output;
}

TEST(SweepInterrupt, ASweepKilledOutrightTakesItsRunningPointsWithIt) {
  for (const bool programs : {false, true}) {
    SCOPED_TRACE(programs ? "points started as programs (--rtsim)" : "points forked");
    const fs::path dir = scratch_dir(programs ? "sweep-killed-programs" : "sweep-killed");
    const fs::path file = write_slow_sweep(dir), out = dir / "out", log = dir / "sweep.log";
    const pid_t pid = start_sweep(file, out, "2", log, programs);
    ASSERT_TRUE(wait_for(out / "points" / "0000" / "run.log", 120)) << read_file(log);
    // The sweep and a point at least (the point's log is opened just before it starts).
    const auto started = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (processes_naming(out.string()) < 2 && std::chrono::steady_clock::now() < started)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_GE(processes_naming(out.string()), 2);
    ::kill(pid, SIGKILL);
    std::string error;
    (void)rtsim::wait_for_child(pid, error);
    // Its points get the parent-death signal and end within moments.
    EXPECT_TRUE(all_gone(out)) << "a point ran on after its sweep was killed";
  }
}

TEST(SweepInterrupt, AnMpiSweepInterruptedWritesThePartialTableToo) {
#ifndef RTSIM_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  // mpirun passes the interrupt on to every rank: over MPI the workers stop their points and
  // report them, rank 0 writes the table of what is done; on one host without MPI (the
  // default) rank 0's local sweep does the same.
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);  // CI containers run as root
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  for (const char* one_host : {"mpi", "jobs"}) {
    SCOPED_TRACE(one_host);
    const fs::path dir = scratch_dir(std::string("sweep-interrupt-mpi-") + one_host);
    const fs::path file = write_slow_sweep(dir), out = dir / "out", log = dir / "mpirun.log";
    std::string error;
    const pid_t pid = rtsim::spawn_logged(
        {RTSIM_MPIEXEC, "-np", "2", "--oversubscribe", RTSIM_BINARY, "sweep", file.string(),
         "--mpi", "--one-host", one_host, "--jobs", "1", "--out", out.string()},
        log, false, error);
    ASSERT_GT(pid, 0) << error;
    ASSERT_TRUE(wait_for(out / "points" / "0001" / "done.json", 120)) << read_file(log);
    ::kill(pid, SIGINT);
    (void)rtsim::wait_for_child(pid, error);
    expect_partial_table(log, out);
    EXPECT_TRUE(all_gone(out));
  }
#endif
}
