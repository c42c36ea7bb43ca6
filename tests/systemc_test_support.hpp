#pragma once
// SystemC allows one elaboration and one simulation per process: after sc_start, no module can
// be built and a second sc_start cannot begin afresh. A test that simulates therefore runs its
// scenario in a forked child:
//
//   TEST(Suite, Scenario) {
//     EXPECT_EQ(rtsim::test::run_in_child([] {
//       Top top("top");                  // elaborate
//       sc_core::sc_start();             // simulate
//       EXPECT_EQ(top.count, 3);         // gtest assertions work in the child
//       return 0;
//     }), 0);
//   }
//
// The child's exit code is the function's return value; it is 1 if the function returned 0 but
// a gtest assertion failed in the child (the failure message is printed by the child), 2 if it
// threw (the message goes to stderr). A child killed by a signal gives 128 + the signal number.
// Each test program still needs `int sc_main(int, char*[]) { return 0; }` for libsystemc to link.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>

namespace rtsim::test {

/// A child that hangs is killed after `alarm_s` seconds (SIGALRM: 128 + 14), so the test fails
/// instead of stalling.
inline int run_in_child(const std::function<int()>& scenario, unsigned alarm_s = 120) {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    ADD_FAILURE() << "fork failed";
    return -1;
  }
  if (pid == 0) {
    ::alarm(alarm_s);
    int code = 0;
    try {
      code = scenario();
      if (code == 0 && ::testing::Test::HasFailure()) code = 1;
    } catch (const std::exception& e) {
      std::cerr << "run_in_child: exception: " << e.what() << "\n";
      code = 2;
    } catch (...) {
      std::cerr << "run_in_child: unknown exception\n";
      code = 2;
    }
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    ::_exit(code);  // no destructors or atexit handlers of the parent's state
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      ADD_FAILURE() << "waitpid failed";
      return -1;
    }
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

}  // namespace rtsim::test
