// gaudet-pert's answers do not hang on which of two threads SystemC runs first at one time.
// That order is the order of the kernel's timed-event queue, which any other event in the
// simulation can change: here a thread that only waits, with its own period, is added to the
// simulation. With a strobe seeing requests made at its very time (bus_interface.hpp), it moved
// the 8-PERT frame time on npp-412 at 64 x 64 by -0.32% (0.5198598 s -> 0.5181986 s).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <systemc>

#include "tests/machine_test_support.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// A thread that does nothing but wait, every `period`: timed events of its own in the queue.
class Bystander : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Bystander);
  Bystander(sc_core::sc_module_name name, sc_core::sc_time period)
      : sc_core::sc_module(name), period_(period) {
    SC_THREAD(run);
  }

 private:
  void run() {
    for (;;) wait(period_);
  }
  sc_core::sc_time period_;
};

/// gaudet-pert on npp-412 at 64 x 64 with `pert_count` PERTs, with a bystander of `period` ps
/// (0: none): the frame time and the machine's own statistics, written to `out` by a child.
json simulate(int pert_count, std::uint64_t period, const std::string& tag) {
  const fs::path out = rtsim::test::scratch_dir(tag) / "result.json";
  fs::create_directories(out.parent_path());
  const int code = rtsim::test::run_in_child([&] {
    auto p = rtsim::test::prepare_machine("gaudet-pert", "builtin:npp-412",
                                          {"pert_count=" + std::to_string(pert_count)});
    std::unique_ptr<Bystander> bystander;
    if (period > 0)
      bystander = std::make_unique<Bystander>("bystander", sc_core::sc_time::from_value(period));
    rtsim::platform::RunOptions opts;
    opts.width = 64;
    opts.height = 64;
    const auto res = p->machine->run(p->scene, p->twin, p->registry, opts);
    json j;
    j["simulated_time_s"] = res.simulated_time_s;
    j["gaudet"] = res.stats.at("gaudet");
    std::ofstream(out) << j.dump();
    return 0;
  });
  EXPECT_EQ(code, 0);
  std::ifstream in(out);
  return in ? json::parse(in) : json();
}

TEST(GaudetPert, FrameTimesDoNotDependOnTheOrderOfThreadsAtOneTime) {
  for (const int perts : {8, 64}) {
    const json alone = simulate(perts, 0, "tie-alone-" + std::to_string(perts));
    ASSERT_TRUE(alone.contains("simulated_time_s"));
    for (const std::uint64_t period : {1000000ULL, 777777ULL}) {  // 1 us, 777.777 ns
      SCOPED_TRACE(std::to_string(perts) + " PERTs, a bystander every " + std::to_string(period) +
                   " ps");
      const json with =
          simulate(perts, period, "tie-" + std::to_string(perts) + "-" + std::to_string(period));
      ASSERT_TRUE(with.contains("simulated_time_s"));
      std::printf("%d PERTs: frame %.9g s alone, %.9g s with a bystander every %llu ps\n", perts,
                  alone["simulated_time_s"].get<double>(), with["simulated_time_s"].get<double>(),
                  static_cast<unsigned long long>(period));
      EXPECT_EQ(alone["simulated_time_s"], with["simulated_time_s"]);
      EXPECT_EQ(alone["gaudet"], with["gaudet"]);
    }
  }
}

}  // namespace
