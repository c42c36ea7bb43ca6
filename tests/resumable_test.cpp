// A processor's program as a coroutine an SC_METHOD runs (modules/resumable.hpp): a call it
// co_awaits runs to its end before the caller goes on, however deep; an exception reaches the
// caller, and one nobody catches leaves the method's activation; frames are reused; and a
// program that waits on time and on events in a method wakes at the times a thread making the
// same waits wakes.
#include "modules/resumable.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <systemc>
#include <vector>

#include "tests/systemc_test_support.hpp"

namespace {

using rtsim::modules::Resumable;
using rtsim::modules::ResumableHost;
using sc_core::SC_NS;
using sc_core::sc_time;

/// A wait outside SystemC: it only suspends (the host resumes it at the next resume()).
struct Pause {
  ResumableHost& host;
  bool await_ready() const noexcept { return false; }
  void await_suspend(std::coroutine_handle<> h) { host.suspended(h); }
  void await_resume() const noexcept {}
};

Resumable leaf(ResumableHost& host, std::vector<std::string>& log, int depth) {
  log.push_back("in " + std::to_string(depth));
  if (depth > 0) {
    co_await Pause{host};
    co_await leaf(host, log, depth - 1);
  }
  log.push_back("out " + std::to_string(depth));
}

TEST(Resumable, ANestedCallRunsToItsEndBeforeItsCallerGoesOn) {
  ResumableHost host;
  std::vector<std::string> log;
  host.start(leaf(host, log, 2));
  EXPECT_TRUE(log.empty());  // not started before the first activation
  EXPECT_FALSE(host.resume());
  EXPECT_EQ(log, (std::vector<std::string>{"in 2"}));
  EXPECT_TRUE(host.resume());
  EXPECT_EQ(log, (std::vector<std::string>{"in 2", "in 1"}));
  EXPECT_FALSE(host.ended());
  host.resume();
  EXPECT_TRUE(host.ended());
  EXPECT_EQ(log, (std::vector<std::string>{"in 2", "in 1", "in 0", "out 0", "out 1", "out 2"}));
  host.resume();  // ended: nothing runs
  EXPECT_EQ(log.size(), 6u);
}

Resumable thrower(ResumableHost& host) {
  co_await Pause{host};
  throw std::overflow_error("time ran out");
}

Resumable catcher(ResumableHost& host, std::string& caught) {
  try {
    co_await thrower(host);
  } catch (const std::overflow_error& e) {
    caught = e.what();
  }
  co_await thrower(host);  // not caught: leaves the activation
}

TEST(Resumable, AnExceptionReachesTheCallerAndUncaughtLeavesTheActivation) {
  ResumableHost host;
  std::string caught;
  host.start(catcher(host, caught));
  host.resume();
  host.resume();
  EXPECT_EQ(caught, "time ran out");
  EXPECT_THROW(host.resume(), std::overflow_error);
  EXPECT_TRUE(host.ended());
}

TEST(Resumable, AFrameFreedIsTheNextOfItsSizeMade) {
  void* a = rtsim::modules::FramePool::get(200);
  rtsim::modules::FramePool::put(a, 200);
  void* b = rtsim::modules::FramePool::get(200);
  EXPECT_EQ(a, b);
  void* big = rtsim::modules::FramePool::get(100000);  // not pooled
  rtsim::modules::FramePool::put(big, 100000);
  rtsim::modules::FramePool::put(b, 200);
}

/// The same waits as a thread and as a program in a method: 10 ns, then an event (fired at 25
/// ns), then 5 ns or the event, whichever first (the event, at 32 ns), then 5 ns again.
struct Waiter : sc_core::sc_module {
  sc_core::sc_event go;
  std::vector<std::uint64_t> thread_ns, method_ns;
  ResumableHost host;
  SC_HAS_PROCESS(Waiter);
  explicit Waiter(const sc_core::sc_module_name& n) : sc_core::sc_module(n) {
    SC_THREAD(thread);
    SC_METHOD(method);
    SC_THREAD(driver);
    host.start(program());
  }
  static std::uint64_t ns() { return sc_core::sc_time_stamp().value() / 1000; }  // ps -> ns
  void driver() {
    sc_core::wait(sc_time(25, SC_NS));
    go.notify();
    sc_core::wait(sc_time(7, SC_NS));
    go.notify();
  }
  void thread() {
    sc_core::wait(sc_time(10, SC_NS));
    thread_ns.push_back(ns());
    sc_core::wait(go);
    thread_ns.push_back(ns());
    sc_core::wait(sc_time(10, SC_NS), go);
    thread_ns.push_back(ns());
    sc_core::wait(sc_time(5, SC_NS));
    thread_ns.push_back(ns());
  }
  void method() { host.resume(); }
  struct After {
    ResumableHost& host;
    sc_time delay;
    const sc_core::sc_event* event;
    bool await_ready() const noexcept { return false; }
    void await_suspend(std::coroutine_handle<> h) {
      host.suspended(h);
      if (event == nullptr)
        sc_core::next_trigger(delay);
      else if (delay == sc_core::SC_ZERO_TIME)
        sc_core::next_trigger(*event);
      else
        sc_core::next_trigger(delay, *event);
    }
    void await_resume() const noexcept {}
  };
  Resumable program() {
    co_await After{host, sc_time(10, SC_NS), nullptr};
    method_ns.push_back(ns());
    co_await After{host, sc_core::SC_ZERO_TIME, &go};
    method_ns.push_back(ns());
    co_await After{host, sc_time(10, SC_NS), &go};
    method_ns.push_back(ns());
    co_await After{host, sc_time(5, SC_NS), nullptr};
    method_ns.push_back(ns());
  }
};

TEST(Resumable, AProgramInAMethodWakesWhenAThreadMakingTheSameWaitsWakes) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              Waiter w("waiter");
              sc_core::sc_start();
              EXPECT_EQ(w.thread_ns, (std::vector<std::uint64_t>{10, 25, 32, 37}));
              EXPECT_EQ(w.method_ns, w.thread_ns);
              EXPECT_TRUE(w.host.ended());
              return 0;
            }),
            0);
}

}  // namespace
