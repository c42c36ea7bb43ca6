// The platform core's modules: PipelinedUnit and Occupancy (plain arithmetic), and, each in a
// forked simulation (SystemC allows one per process), the TimedFifo between two temporally
// decoupled threads, the TLM message queue's back-pressure, and the TLM memory.
#include <gtest/gtest.h>
#include <tlm_utils/simple_initiator_socket.h>

#include <systemc>

#include "modules/local_clock.hpp"
#include "modules/memory.hpp"
#include "modules/message_channel.hpp"
#include "modules/occupancy.hpp"
#include "modules/pipelined_unit.hpp"
#include "modules/statistics.hpp"
#include "tests/systemc_test_support.hpp"

extern "C" int sc_main(int, char*[]) { return 0; }

using sc_core::SC_NS;
using sc_core::sc_time;
using sc_core::SC_US;
using namespace rtsim::modules;

TEST(PipelinedUnit, AdvancesTimeByArithmetic) {
  // Ullner's pipe: 17 stages at 1/3 us (seed 000 L588): 1000 polygons take 1000 intervals and
  // the last result leaves 17 stages after it entered.
  PipelinedUnit pipe("pipe", sc_time(333333, sc_core::SC_PS), 17);
  const auto a = pipe.issue(1000, sc_time(0, SC_NS));
  EXPECT_EQ(a.first_issue, sc_time(0, SC_NS));
  EXPECT_EQ(a.next_free, sc_time(333333000, sc_core::SC_PS));
  EXPECT_EQ(a.done, a.next_free - pipe.interval() + pipe.latency());
  EXPECT_EQ(pipe.latency(), sc_time(5666661, sc_core::SC_PS));
  // A second batch offered early waits for the first; one offered late starts when offered.
  const auto b = pipe.issue(10, sc_time(1, SC_US));
  EXPECT_EQ(b.first_issue, a.next_free);
  const auto c = pipe.issue(1, sc_time(1, sc_core::SC_SEC));
  EXPECT_EQ(c.first_issue, sc_time(1, sc_core::SC_SEC));
  EXPECT_EQ(pipe.issued(), 1011u);
  EXPECT_EQ(pipe.busy(), sc_time::from_value(333333ull * 1011));
}

TEST(Occupancy, TimeWeightedMeanAndMaximum) {
  Occupancy o;
  // puts at 0, 10, 20; gets at 10, 30, 40 (ns): level 1 on [0,20), 2 on [20,30), 1 on [30,40).
  for (int t : {0, 10, 20}) o.put(sc_time(t, SC_NS));
  for (int t : {10, 30, 40}) o.got(sc_time(t, SC_NS));
  const auto s = o.summarize(sc_time(0, SC_NS), sc_time(40, SC_NS));
  EXPECT_EQ(s.max, 2);  // the hand-over at 10 counts the get first
  EXPECT_DOUBLE_EQ(s.mean, (1.0 * 20 + 2.0 * 10 + 1.0 * 10) / 40.0);
  const auto late = o.summarize(sc_time(20, SC_NS), sc_time(40, SC_NS));
  EXPECT_DOUBLE_EQ(late.mean, (2.0 * 10 + 1.0 * 10) / 20.0);
}

TEST(LatencyRecorder, NearestRankPercentiles) {
  LatencyRecorder r;
  for (int i = 1; i <= 100; ++i) r.add(sc_time(i, SC_US));
  const auto j = r.to_json();
  EXPECT_EQ(j["count"], 100);
  EXPECT_DOUBLE_EQ(j["p50"].get<double>(), 50e-6);
  EXPECT_DOUBLE_EQ(j["p99"].get<double>(), 99e-6);
  EXPECT_DOUBLE_EQ(j["max"].get<double>(), 100e-6);
  EXPECT_NEAR(j["mean"].get<double>(), 50.5e-6, 1e-15);
  std::uint64_t n = 0;
  for (const auto& c : j["histogram"]["counts"]) n += c.get<std::uint64_t>();
  EXPECT_EQ(n, 100u);
}

namespace {

/// A producer that puts one item every `period` and a consumer that needs `service` for each,
/// through a FIFO of depth `depth`, both temporally decoupled by the global quantum.
struct FifoBench : sc_core::sc_module {
  TimedFifo<int> fifo;
  sc_time period, service;
  int items;
  std::vector<sc_time> put_at, got_at;
  SC_HAS_PROCESS(FifoBench);
  FifoBench(sc_core::sc_module_name n, std::size_t depth, sc_time p, sc_time s, int count)
      : sc_core::sc_module(n), fifo("fifo", depth), period(p), service(s), items(count) {
    SC_THREAD(produce);
    SC_THREAD(consume);
  }
  void produce() {
    LocalClock c;
    for (int i = 0; i < items; ++i) {
      c.advance(period);
      put_at.push_back(fifo.put(i, c.now()));
      c.catch_up(put_at.back());
    }
  }
  void consume() {
    LocalClock c;
    for (int i = 0; i < items; ++i) {
      if (fifo.empty()) {
        c.sync();
        while (fifo.empty()) sc_core::wait(fifo.put_event());
        c.resync();
      }
      sc_time t;
      EXPECT_EQ(fifo.get(c.now(), t), i);
      got_at.push_back(t);
      c.catch_up(t);
      c.advance(service);
    }
  }
};

/// Runs a FifoBench at a quantum and checks the timestamps against the closed form: a slow
/// consumer (service > period) takes item i at i * service + period, and back-pressure makes
/// item i enter no earlier than the time item i - depth was taken.
int fifo_scenario(sc_time quantum) {
  tlm::tlm_global_quantum::instance().set(quantum);
  const sc_time period(10, SC_NS), service(25, SC_NS);
  const std::size_t depth = 3;
  FifoBench bench("bench", depth, period, service, 50);
  sc_core::sc_start();
  for (std::size_t i = 0; i < 50; ++i) {
    EXPECT_EQ(bench.got_at[i], period + static_cast<double>(i) * service) << "item " << i;
    if (i >= depth) {
      EXPECT_GE(bench.put_at[i], bench.got_at[i - depth]) << "item " << i;
    }
    EXPECT_GE(bench.got_at[i], bench.put_at[i]);
  }
  const auto occ = bench.fifo.occupancy().summarize(sc_time(0, SC_NS), bench.got_at.back());
  EXPECT_LE(occ.max, static_cast<int>(depth));
  return ::testing::Test::HasFailure() ? 1 : 0;
}

}  // namespace

TEST(TimedFifo, ExactTimingAndBackPressureAtQuantumZero) {
  EXPECT_EQ(rtsim::test::run_in_child([] { return fifo_scenario(sc_time(0, SC_NS)); }), 0);
}

TEST(TimedFifo, SameTimestampsWithALargeQuantum) {
  // The FIFO's own timing does not depend on how far the threads run ahead.
  EXPECT_EQ(rtsim::test::run_in_child([] { return fifo_scenario(sc_time(1, SC_US)); }), 0);
}

namespace {

struct Message {
  int value;
};

struct Sender : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<Sender> out;
  std::vector<sc_time> accepted;
  SC_HAS_PROCESS(Sender);
  explicit Sender(sc_core::sc_module_name n) : sc_core::sc_module(n), out("out") { SC_THREAD(run); }
  void run() {
    LocalClock c;
    for (int i = 0; i < 6; ++i) {
      Message m{i};
      accepted.push_back(send_message(out, m, c.now(), 8 * sizeof(Message)));
      c.catch_up(accepted.back());
      c.advance(sc_time(1, SC_NS));
    }
  }
};

struct Receiver : sc_core::sc_module {
  MessageQueue<Message> queue;
  std::vector<int> values;
  SC_HAS_PROCESS(Receiver);
  explicit Receiver(sc_core::sc_module_name n) : sc_core::sc_module(n), queue("queue", 2) {
    SC_THREAD(run);
  }
  void run() {
    LocalClock c;
    for (int i = 0; i < 6; ++i) {
      if (queue.fifo.empty()) {
        c.sync();
        while (queue.fifo.empty()) sc_core::wait(queue.fifo.put_event());
        c.resync();
      }
      sc_time t;
      values.push_back(queue.fifo.get(c.now(), t).value);
      c.catch_up(t);
      c.advance(sc_time(100, SC_NS));  // slow: the sender must wait for room
    }
  }
};

}  // namespace

TEST(MessageQueue, TlmTransportWithBackPressure) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              Sender s("sender");
              Receiver r("receiver");
              s.out.bind(r.queue.socket);
              sc_core::sc_start();
              EXPECT_EQ(r.values, (std::vector<int>{0, 1, 2, 3, 4, 5}));
              // Depth 2: messages 0 and 1 enter at once (0 and 1 ns); message 2 waits for
              // message 0 to be taken (at 0 ns, then 100 ns of service: taken 1 at 100 ns).
              EXPECT_EQ(s.accepted[0], sc_time(0, SC_NS));
              EXPECT_EQ(s.accepted[1], sc_time(1, SC_NS));
              EXPECT_GE(s.accepted[2], sc_time(0, SC_NS));
              EXPECT_GE(s.accepted[3], sc_time(100, SC_NS));
              EXPECT_GE(s.accepted[5], sc_time(300, SC_NS));
              return ::testing::Test::HasFailure() ? 1 : 0;
            }),
            0);
}

namespace {

struct MemoryUser : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<MemoryUser> out;
  Memory* mem;
  SC_HAS_PROCESS(MemoryUser);
  MemoryUser(sc_core::sc_module_name n, Memory& m) : sc_core::sc_module(n), out("out"), mem(&m) {
    SC_THREAD(run);
  }
  void run() {
    std::array<std::uint32_t, 20> line{};
    for (unsigned i = 0; i < 20; ++i) line[i] = 100 + i;
    tlm::tlm_generic_payload gp;
    sc_time delay = sc_core::SC_ZERO_TIME;
    gp.set_command(tlm::TLM_WRITE_COMMAND);
    gp.set_address(2 * 80);
    gp.set_data_ptr(reinterpret_cast<unsigned char*>(line.data()));
    gp.set_data_length(80);
    gp.set_streaming_width(80);
    gp.set_byte_enable_ptr(nullptr);
    out->b_transport(gp, delay);
    EXPECT_EQ(gp.get_response_status(), tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(delay, sc_time(20, SC_US));  // 20 words through the load port at 1 us
    EXPECT_EQ(mem->contents()[40], 100u);
    EXPECT_EQ(mem->contents()[59], 119u);
    std::array<std::uint32_t, 20> back{};
    gp.set_command(tlm::TLM_READ_COMMAND);
    gp.set_data_ptr(reinterpret_cast<unsigned char*>(back.data()));
    delay = sc_core::SC_ZERO_TIME;
    out->b_transport(gp, delay);
    EXPECT_EQ(back, line);
    EXPECT_EQ(delay, sc_time::from_value(333333));  // one line: all 20 banks in one cycle
    gp.set_address(4 * 80);                         // past the end
    out->b_transport(gp, delay);
    EXPECT_EQ(gp.get_response_status(), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(mem->words_written(), 20u);
    EXPECT_EQ(mem->lines_read(), 1u);
  }
};

}  // namespace

TEST(Memory, TlmReadsWritesTimingAndErrors) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              // 4 lines of 20 words; loading costs 1 us a word, reading 1/3 us a line.
              Memory mem("mem", 80, 20, sc_time(1, SC_US), sc_time::from_value(333333));
              MemoryUser user("user", mem);
              user.out.bind(mem.socket);
              sc_core::sc_start();
              return ::testing::Test::HasFailure() ? 1 : 0;
            }),
            0);
}
