// modules::Link: latency plus ceil(bits / lanes) bit times, messages in the order handed over,
// back-pressure counted, a sender slower than the link holding it, and its busy time.
#include "modules/link.hpp"

#include <gtest/gtest.h>

#include <systemc>

#include "modules/module_params.hpp"
#include "params/registry.hpp"

namespace {

using rtsim::modules::Link;
using rtsim::modules::ModuleParams;
using rtsim::modules::ParamDecls;
using sc_core::SC_NS;
using sc_core::sc_time;

Link make_link(const std::string& latency, const std::string& lanes, const std::string& rate) {
  rtsim::params::ParamRegistry r;  // the link reads its parameters when it is built
  Link::declare_params(ParamDecls(r, "wire"),
                       {.latency = latency, .lanes = lanes, .bit_rate = rate, .source = "test"});
  return Link(ModuleParams(r, "wire"));
}

TEST(Link, SerialisationIsCeilOfBitsOverLanesBitTimes) {
  // A bit-serial wire at 150 ns a bit (seed 000 L733): 32 bits take 4.8 us.
  const Link serial = make_link("0 s", "1", "6.666666666666667 Mbit/s");
  EXPECT_EQ(serial.serialisation(32), sc_time(4800, SC_NS));
  // 13 wires carry 416 bits in 32 bit times (L731-L733): about five microseconds.
  const Link thirteen = make_link("0 s", "13", "6.666666666666667 Mbit/s");
  EXPECT_EQ(thirteen.serialisation(416), sc_time(4800, SC_NS));
  EXPECT_EQ(thirteen.serialisation(417), sc_time(4950, SC_NS));  // one more bit time
  // A word-parallel bus: a 7-word message in 7 word times.
  const Link bus = make_link("0 s", "32", "5 Mbit/s");
  EXPECT_EQ(bus.serialisation(7 * 32), sc_time(1400, SC_NS));
}

TEST(Link, MessagesQueueBehindEachOtherAndArriveAfterTheLatency) {
  Link l = make_link("100 ns", "32", "5 Mbit/s");  // 200 ns a word
  // Two 2-word messages handed over at once: the second waits for the first.
  EXPECT_EQ(l.transfer(64, sc_time(0, SC_NS)), sc_time(400 + 100, SC_NS));
  EXPECT_EQ(l.transfer(64, sc_time(0, SC_NS)), sc_time(800 + 100, SC_NS));
  EXPECT_EQ(l.waited(), sc_time(400, SC_NS));
  // A message handed over after the link is free again starts at once.
  EXPECT_EQ(l.transfer(32, sc_time(2000, SC_NS)), sc_time(2200 + 100, SC_NS));
  EXPECT_EQ(l.messages(), 3u);
  EXPECT_EQ(l.bits(), 160u);
  EXPECT_EQ(l.busy(), sc_time(1000, SC_NS));
}

TEST(Link, ASlowerSenderHoldsTheLinkUntilItsLastWord) {
  Link l = make_link("0 s", "32", "5 Mbit/s");
  // 3 words the sender writes from 0 to 1 us (slower than the link's 600 ns): the last word
  // arrives when it is written, not before.
  EXPECT_EQ(l.transfer(96, sc_time(0, SC_NS), sc_time(1000, SC_NS)), sc_time(1000, SC_NS));
  EXPECT_EQ(l.busy(), sc_time(1000, SC_NS));
  // A faster sender: the link's own pace.
  EXPECT_EQ(l.transfer(96, sc_time(1000, SC_NS), sc_time(1100, SC_NS)), sc_time(1600, SC_NS));
}

}  // namespace
