// The fork servers of an MPI rank (app/fork_server.hpp): each request runs in a child forked by
// a server started before any, with its output in its log; its pid comes first, its wait status
// when it ends; several slots run side by side; a log that cannot be written is an error, not a
// hang. The fake runs say --image none, so the servers do not load the image module. (`rtsim sweep
// --mpi` and `rtsim validate --mpi` run through them: sweep_mpi_test.cpp.)
#include "app/fork_server.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <thread>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::app::ForkServers;
using rtsim::test::read_file;
using rtsim::test::scratch_dir;

namespace {

/// What a run does here: prints its argument and its pid, sleeps if asked, exits 3 for "fail".
int fake_run(const std::vector<std::string>& args) {
  std::cout << "ran " << args.at(1) << " in " << ::getpid() << "\n";
  if (args.at(1) == "sleep") std::this_thread::sleep_for(std::chrono::milliseconds(300));
  return args.at(1) == "fail" ? 3 : 0;
}

}  // namespace

TEST(ForkServers, RunsEachRequestInAChildWithItsLogAndItsStatus) {
  const fs::path dir = scratch_dir("fork-servers");
  fs::create_directories(dir);
  ForkServers servers(2, fake_run);
  pid_t child = -1;
  std::string error;
  const int ok = servers.run_and_wait(
      {"rtsim", "hello", "--image", "none"}, dir / "a.log", [&](pid_t pid) { child = pid; }, error);
  EXPECT_EQ(error, "");
  ASSERT_TRUE(WIFEXITED(ok));
  EXPECT_EQ(WEXITSTATUS(ok), 0);
  EXPECT_GT(child, 0);
  EXPECT_NE(child, ::getpid());
  EXPECT_EQ(read_file(dir / "a.log"), "ran hello in " + std::to_string(child) + "\n");

  const int failed = servers.run_and_wait(
      {"rtsim", "fail", "--image", "none"}, dir / "b.log", [](pid_t) {}, error);
  ASSERT_TRUE(WIFEXITED(failed));
  EXPECT_EQ(WEXITSTATUS(failed), 3);

  // A log that cannot be written: an error at once, and the server goes on.
  const int bad = servers.run_and_wait(
      {"rtsim", "x", "--image", "none"}, dir / "no" / "such" / "c.log",
      [](pid_t) { ADD_FAILURE() << "nothing started"; }, error);
  EXPECT_EQ(bad, -1);
  EXPECT_NE(error.find("cannot write"), std::string::npos) << error;
  error.clear();
  EXPECT_EQ(servers.run_and_wait(
                {"rtsim", "again", "--image", "none"}, dir / "d.log", [](pid_t) {}, error),
            0);
  fs::remove_all(dir);
}

TEST(ForkServers, TwoSlotsRunSideBySide) {
  const fs::path dir = scratch_dir("fork-servers-two");
  fs::create_directories(dir);
  ForkServers servers(2, fake_run);
  std::atomic<int> running{0}, most{0};
  const auto one = [&](const std::string& log) {
    std::string error;
    const int status = servers.run_and_wait(
        {"rtsim", "sleep", "--image", "none"}, dir / log,
        [&](pid_t) {
          const int now = ++running;
          int seen = most.load();
          while (now > seen && !most.compare_exchange_weak(seen, now)) {
          }
        },
        error);
    --running;
    EXPECT_EQ(status, 0) << error;
  };
  std::thread a(one, "a.log"), b(one, "b.log");
  a.join();
  b.join();
  EXPECT_EQ(most.load(), 2) << "the second request waited for the first";
  fs::remove_all(dir);
}
