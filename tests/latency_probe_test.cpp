#include "modules/latency_probe.hpp"

#include <gtest/gtest.h>

using rtsim::modules::LatencyPart;
using rtsim::modules::LatencyProbe;
using sc_core::SC_NS;
using sc_core::sc_time;

TEST(LatencyProbe, DisabledRecordsNothing) {
  LatencyProbe p;
  const int s = p.stage("cpu");
  const auto j = p.begin(sc_time(0, SC_NS));
  EXPECT_EQ(j, LatencyProbe::kNoJourney);
  p.add(j, s, LatencyPart::kService, sc_time(5, SC_NS));
  p.end(j, sc_time(5, SC_NS));
  EXPECT_EQ(p.rays(), 0u);
  EXPECT_EQ(p.to_json()["rays"], 0);
}

TEST(LatencyProbe, SumsPartsPerStageAndReportsTheUnattributedRest) {
  LatencyProbe p(true);
  const int q = p.stage("queue");
  const int cpu = p.stage("cpu");
  // Ray A: 10 ns queueing, 30 ns service, 5 ns transfer, ends at 50 ns: 5 ns unattributed.
  const auto a = p.begin(sc_time(0, SC_NS));
  // Ray B overlaps A and meets only the cpu: 20 ns service, ends exactly.
  const auto b = p.begin(sc_time(10, SC_NS));
  p.add(a, q, LatencyPart::kQueueing, sc_time(10, SC_NS));
  p.add(a, cpu, LatencyPart::kService, sc_time(30, SC_NS));
  p.add(b, cpu, LatencyPart::kService, sc_time(20, SC_NS));
  p.add(a, cpu, LatencyPart::kTransfer, sc_time(5, SC_NS));
  EXPECT_EQ(p.in_flight(), 2u);
  p.end(b, sc_time(30, SC_NS));
  p.end(a, sc_time(50, SC_NS));
  EXPECT_EQ(p.in_flight(), 0u);
  // A freed slot is reused and starts empty.
  const auto c = p.begin(sc_time(60, SC_NS));
  p.add(c, cpu, LatencyPart::kService, sc_time(10, SC_NS));
  p.end(c, sc_time(70, SC_NS));

  const auto j = p.to_json();
  EXPECT_EQ(j["rays"], 3);
  EXPECT_NEAR(j["end_to_end_s"]["mean"].get<double>(), (50e-9 + 20e-9 + 10e-9) / 3, 1e-15);
  EXPECT_NEAR(j["unattributed_s"].get<double>(), 5e-9 / 3, 1e-15);
  const auto& s = j["stages"];
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.begin().key(), "queue");  // the order stages were named in
  EXPECT_NEAR(s["queue"]["queueing_s"].get<double>(), 10e-9 / 3, 1e-15);
  EXPECT_NEAR(s["cpu"]["service_s"].get<double>(), 60e-9 / 3, 1e-15);
  EXPECT_NEAR(s["cpu"]["transfer_s"].get<double>(), 5e-9 / 3, 1e-15);
  EXPECT_NEAR(s["cpu"]["total_s"].get<double>(), 65e-9 / 3, 1e-15);
  EXPECT_NEAR(s["cpu"]["p99_s"].get<double>(), 35e-9, 1e-15);
  EXPECT_NEAR(s["cpu"]["share"].get<double>(), 65.0 / 80.0, 1e-12);
}
