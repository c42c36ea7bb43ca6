// The kit's event queue for many event-driven processors (modules/wake_queue.hpp): its clients
// run at the times they ask for, a sooner wake replaces a later one and a later one leaves the
// sooner standing, clients due at one time run first asked first run (those woken for now by a
// client that runs included), and a wake asked for by a SystemC process outside the queue makes
// SystemC run the queue then; and that the queue runs its clients ahead of SystemC only until
// something else is due, their time the wake's and a delay they hand SystemC counted from its own.
#include "modules/wake_queue.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <systemc>
#include <vector>

#include "modules/sim_time.hpp"
#include "tests/systemc_test_support.hpp"

namespace {

using rtsim::modules::WakeQueue;
using sc_core::SC_NS;
using sc_core::sc_time;

/// A client that logs its runs ("name@ns") and runs a script step on each.
struct Logged final : WakeQueue::Client {
  Logged(const char* n, std::vector<std::string>& l) : name(n), log(&l) {}
  std::string name;
  std::vector<std::string>* log;
  std::function<void()> on_run;
  void woken() override {
    std::string run = name;  // "a@10": the client and the time in ns
    run += '@';
    run += std::to_string(rtsim::modules::sim_now().value() / sc_time(1, SC_NS).value());
    log->push_back(run);
    if (on_run) on_run();
  }
};

/// Fires `start` at 10 ns, then at 35 ns (outside the queue) asks for client `k` at 40 ns.
struct Starter : sc_core::sc_module {
  sc_core::sc_event start;
  WakeQueue* queue = nullptr;
  std::size_t outside_client = 0;
  SC_HAS_PROCESS(Starter);
  explicit Starter(const sc_core::sc_module_name& n) : sc_core::sc_module(n) { SC_THREAD(run); }
  void run() {
    start.notify(sc_time(10, SC_NS));
    sc_core::wait(sc_time(35, SC_NS));
    queue->wake_at(outside_client, sc_time(40, SC_NS));
  }
};

TEST(WakeQueue, RunsEachClientWhenItAsksFirstAskedFirstRun) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              Starter starter("starter");
              WakeQueue queue("queue", starter.start);
              starter.queue = &queue;
              std::vector<std::string> log;
              Logged a("a", log), b("b", log), c("c", log);
              const std::size_t ka = queue.add(a), kb = queue.add(b), kc = queue.add(c);
              starter.outside_client = kc;
              int a_runs = 0;
              a.on_run = [&] {
                ++a_runs;
                // Its first run (10 ns, b and c due too): again now, after them.
                if (a_runs == 1) queue.wake_at(ka, sc_time(10, SC_NS));
                if (a_runs != 2) return;
                // Its second: c for 20 ns; b for 30 ns, then sooner for 20 ns (it runs after c,
                // asked for first), then for 50 ns, which leaves the sooner standing.
                queue.wake_at(kc, sc_time(20, SC_NS));
                queue.wake_at(kb, sc_time(30, SC_NS));
                queue.wake_at(kb, sc_time(20, SC_NS));
                queue.wake_at(kb, sc_time(50, SC_NS));
              };
              sc_core::sc_start();
              const std::vector<std::string> expected{"a@10", "b@10", "c@10", "a@10",
                                                      "c@20", "b@20", "c@40"};
              EXPECT_EQ(log, expected);
              EXPECT_EQ(queue.wakes(), expected.size());
              return 0;
            }),
            0);
}

TEST(WakeQueue, AWakeInThePastIsADefect) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              Starter starter("starter");
              WakeQueue queue("queue", starter.start);
              std::vector<std::string> log;
              Logged a("a", log);
              const std::size_t ka = queue.add(a);
              bool threw = false;
              a.on_run = [&] {
                try {
                  queue.wake_at(ka, sc_time(5, SC_NS));
                } catch (const std::logic_error&) {
                  threw = true;
                }
              };
              starter.queue = &queue;
              starter.outside_client = ka;
              sc_core::sc_start();
              EXPECT_TRUE(threw);
              return 0;
            }),
            0);
}

/// A SystemC thread that logs what the queue's clients have logged by 25 ns, and another that
/// logs when `event` fires.
struct Watcher : sc_core::sc_module {
  sc_core::sc_event event;
  std::vector<std::string>* log = nullptr;
  std::size_t seen_at_25 = 0;
  SC_HAS_PROCESS(Watcher);
  explicit Watcher(const sc_core::sc_module_name& n) : sc_core::sc_module(n) {
    SC_THREAD(at_25);
    SC_THREAD(on_event);
  }
  void at_25() {
    sc_core::wait(sc_time(25, SC_NS));
    seen_at_25 = log->size();
    log->push_back("watcher@25");
  }
  void on_event() {
    sc_core::wait(event);
    log->push_back("event@" +
                   std::to_string(sc_core::sc_time_stamp().value() / sc_time(1, SC_NS).value()));
  }
};

TEST(WakeQueue, RunsAheadOfSystemCOnlyUntilSomethingElseIsDue) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              Starter starter("starter");
              Watcher watcher("watcher");
              WakeQueue queue("queue", starter.start);
              starter.queue = &queue;
              std::vector<std::string> log;
              watcher.log = &log;
              Logged a("a", log), c("c", log);
              const std::size_t ka = queue.add(a);
              starter.outside_client = queue.add(c);  // at 40 ns, asked for at 35 ns
              c.on_run = [] {};
              int runs = 0;
              a.on_run = [&] {
                ++runs;
                if (runs == 1) queue.wake_at(ka, sc_time(12, SC_NS));
                if (runs == 2) {
                  // Run ahead of SystemC (nothing else is due before 25 ns): an event for
                  // 22 ns counts from SystemC's time, which is still 10 ns.
                  EXPECT_EQ(rtsim::modules::systemc_now(), sc_time(10, SC_NS));
                  watcher.event.notify(sc_time(22, SC_NS) - rtsim::modules::systemc_now());
                  queue.wake_at(ka, sc_time(24, SC_NS));
                }
                if (runs == 3) {
                  // Not ahead of the event at 22 ns: SystemC's time is this wake's.
                  EXPECT_EQ(rtsim::modules::systemc_now(), sc_time(24, SC_NS));
                  queue.wake_at(ka, sc_time(30, SC_NS));
                }
              };
              sc_core::sc_start();
              const std::vector<std::string> expected{"a@10", "c@10",       "a@12", "event@22",
                                                      "a@24", "watcher@25", "a@30", "c@40"};
              EXPECT_EQ(log, expected);
              EXPECT_EQ(watcher.seen_at_25, 5u);
              return 0;
            }),
            0);
}

}  // namespace
