// What one SystemC wait costs on this machine: the floor under any model whose threads wait
// once per step (docs/benchmarks.md, "gaudet-pert: the floor").
//
// BM_TimedWait/N: N threads each wait(d) in a loop, thread i with its own period, so that their
// wake-ups interleave as a machine's processors do; items_per_second is waits (each a timed
// event, a trip through the scheduler and two coroutine switches).
// BM_HandOff/N: N pairs of threads; in each, one notifies an event a time ahead and the other
// waits on it (a message between two processors); items_per_second is hand-offs.
//
// SystemC allows one elaboration per process, so every benchmark's threads are built before the
// first sc_start and sleep on their own event while another benchmark runs.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

namespace {

constexpr int kMaxThreads = 192;  // gaudet-pert's three processors a PERT at 64 PERTs

enum class Kind { kNone, kTimedWait, kHandOff };

struct Bench {
  Kind active = Kind::kNone;
  int threads = 0;
  std::uint64_t count = 0;
};
Bench& bench() {
  static Bench b;
  return b;
}
/// Whether the benchmark of `kind` runs and takes thread (or pair) `index` part.
bool runs(Kind kind, int index) { return bench().active == kind && index < bench().threads; }

// A thread that waits with its own period while its benchmark runs with enough threads.
class Waiter : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Waiter);
  Waiter(sc_core::sc_module_name name, int index)
      : sc_core::sc_module(name), index_(index), period_(10 + 3 * index, sc_core::SC_NS) {
    SC_THREAD(run);
  }
  sc_core::sc_event go;
  int index_;

 private:
  void run() {
    for (;;) {
      while (!runs(Kind::kTimedWait, index_)) wait(go);
      wait(period_);
      ++bench().count;
    }
  }
  sc_core::sc_time period_;
};

// Two threads passing a message: the sender notifies `message` a time ahead, the receiver waits
// on it, then the sender waits for the receiver's answer in turn.
class Pair : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Pair);
  Pair(sc_core::sc_module_name name, int index)
      : sc_core::sc_module(name), index_(index), delay_(7 + 2 * index, sc_core::SC_NS) {
    SC_THREAD(send);
    SC_THREAD(receive);
  }
  sc_core::sc_event go;
  int index_;

 private:
  void send() {
    for (;;) {
      while (!runs(Kind::kHandOff, index_)) wait(go);
      message_.notify(delay_);
      wait(answer_);
    }
  }
  void receive() {
    for (;;) {
      wait(message_);
      ++bench().count;
      answer_.notify(delay_);
    }
  }
  sc_core::sc_time delay_;
  sc_core::sc_event message_, answer_;
};

struct Model {
  std::vector<std::unique_ptr<Waiter>> waiters;
  std::vector<std::unique_ptr<Pair>> pairs;
  Model() {
    // (Appends, not `literal + std::string&&`: GCC bug 105651.)
    for (int i = 0; i < kMaxThreads; ++i) {
      std::string w = "w", p = "p";
      w += std::to_string(i);
      p += std::to_string(i);
      waiters.push_back(std::make_unique<Waiter>(w.c_str(), i));
      pairs.push_back(std::make_unique<Pair>(p.c_str(), i));
    }
  }
};
Model& model() {
  static Model m;
  return m;
}

void run(benchmark::State& state, Kind kind) {
  Model& m = model();
  bench().active = kind;
  bench().threads = static_cast<int>(state.range(0));
  for (int i = 0; i < bench().threads; ++i) {
    m.waiters[static_cast<std::size_t>(i)]->go.notify(sc_core::SC_ZERO_TIME);
    m.pairs[static_cast<std::size_t>(i)]->go.notify(sc_core::SC_ZERO_TIME);
  }
  std::uint64_t done = 0;
  for (auto _ : state) {
    const std::uint64_t before = bench().count;
    sc_core::sc_start(sc_core::sc_time(100, sc_core::SC_US));
    done += bench().count - before;
  }
  bench().active = Kind::kNone;
  // Let the threads of this benchmark go back to sleep on their events.
  sc_core::sc_start(sc_core::sc_time(1, sc_core::SC_US));
  state.SetItemsProcessed(static_cast<std::int64_t>(done));
}

void BM_TimedWait(benchmark::State& state) { run(state, Kind::kTimedWait); }
void BM_HandOff(benchmark::State& state) { run(state, Kind::kHandOff); }

BENCHMARK(BM_TimedWait)->Arg(1)->Arg(3)->Arg(24)->Arg(kMaxThreads)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HandOff)->Arg(1)->Arg(3)->Arg(24)->Arg(kMaxThreads)->Unit(benchmark::kMicrosecond);

}  // namespace
