// SystemC links and runs: a module with one thread advances simulated time as annotated.
#include <gtest/gtest.h>

#include <systemc>

namespace {

struct Ticker : sc_core::sc_module {
  int ticks = 0;
  SC_HAS_PROCESS(Ticker);
  explicit Ticker(sc_core::sc_module_name name) : sc_core::sc_module(name) { SC_THREAD(run); }
  void run() {
    for (int i = 0; i < 3; ++i) {
      wait(sc_core::sc_time(400, sc_core::SC_NS));
      ++ticks;
    }
  }
};

}  // namespace

int sc_main(int, char*[]) { return 0; }

TEST(SystemCSmoke, ThreadAdvancesTimeByAnnotatedDelays) {
  Ticker ticker("ticker");
  sc_core::sc_start();
  EXPECT_EQ(ticker.ticks, 3);
  EXPECT_EQ(sc_core::sc_time_stamp(), sc_core::sc_time(1200, sc_core::SC_NS));
}
