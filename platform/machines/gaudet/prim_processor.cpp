#include "platform/machines/gaudet/prim_processor.hpp"

#include "firmware/tasks/pert_task_costs.hpp"

namespace rtsim::platform::gaudet {

PrimProcessor::PrimProcessor(sc_core::sc_module_name name, const functional::ShellSearch& search,
                             const std::vector<std::uint32_t>& packet_words,
                             const std::vector<Cost>& test_cost, modules::PacketPort& port,
                             const ProcessorConfig& config, std::size_t input_depth,
                             TraceCounters& counters, MachineTrace& trace)
    : PertProcessor(name, config.timing, trace),
      input("input", input_depth),
      out("out"),
      search_(search),
      packet_words_(packet_words),
      test_cost_(test_cost),
      port_(port),
      // At most two IDs ahead (L910, L1056), and no more than it has buffers: packets come in
      // broadcast order, not t order, so with one buffer a second packet could take the only
      // buffer while the ray waits for the first, for ever.
      ahead_(std::max<std::size_t>(1, std::min<std::size_t>(2, config.buffers))),
      counters_(counters) {
  SC_THREAD(run);
}

void PrimProcessor::ask(const ShellToPrim& msg, std::size_t k, RayTicket& t) {
  if (k >= msg.leaf_shells.size() || asked_[k]) return;
  compute_for(t, Stage::kPrim, tasks::kAskPacketCost, "ask");
  asked_[k] = port_.request(msg.leaf_shells[k].child_index, clock_.now());
}

void PrimProcessor::serve(ShellToPrim& msg) {
  PrimToShade res{msg.ticket, false, {}};
  RayTicket& t = res.ticket;  // the ray's journey goes on in the answer
  // Until now (taken) the ray waited in the input queue.
  probe_->to(t, Stage::kShellToPrim, RayProbe::Part::kQueueing, clock_.now());
  compute_for(t, Stage::kPrim, tasks::words_cost(msg.words()), "ray");
  const shading::TracedRay& r = msg.ticket.ray;
  // The answer, as the twin computes it (same search, same kernels).
  TraceCounters c;
  accel::ShellTraversalStats st;
  res.found = r.kind == RayKind::Shadow
                  ? search_.any_hit(r.ray, msg.ticket.t_min, r.t_max, c, st)
                  : search_.closest_hit(r.ray, msg.ticket.t_min, r.t_max, res.hit, c, st);
  counters_ += c;
  if (st.leaf_shells_sorted != msg.leaf_shells.size()) ++list_mismatches_;
  const std::size_t n = msg.leaf_shells.size();
  const std::size_t k = std::min<std::size_t>(st.leaf_shells_tested, n);
  prim_tests_ += st.prim_tests;

  // Play the packets that search needed through the BIC, in t order (Fig. 4-12).
  asked_.assign(n, false);
  if (k > 0) ++rays_with_packets_;
  const sc_core::sc_time asked_first = clock_.now();
  for (std::size_t a = 0; a < ahead_; ++a) ask(msg, a, t);
  std::uint64_t tests_done = 0;
  for (std::size_t j = 0; j < k; ++j) {
    const std::uint32_t id = msg.leaf_shells[j].child_index;
    std::optional<modules::ReceivedPacket> p;
    while (!(p = port_.take(clock_.now(), id))) {
      if (!asked_[j]) {
        if (port_.register_free(clock_.now())) {
          // Till now the ray waited for an ID register.
          probe_->to(t, Stage::kPrimBus, RayProbe::Part::kQueueing, clock_.now());
          ask(msg, j, t);
          continue;
        }
        // Registers free as packets arrive.
        idle(port_.next_arrival(), port_.changed_event(), true);
      } else {
        idle(port_.next_arrival(id), port_.changed_event(), true);
      }
    }
    if (j == 0) {
      first_packet_total_ += p->arrival - asked_first;
      ++first_packets_;
    }
    ++packets_;
    // The primitives are tested in packet order; a light ray stops at its first hit.
    const auto slots = search_.tree().prim_packet(id);
    const std::uint64_t tests = std::min<std::uint64_t>(slots.size(), st.prim_tests - tests_done);
    tests_done += tests;
    Cost work =
        tasks::words_cost(packet_words_[id]) + tasks::kPacketBookkeepingCost + tasks::kStopTestCost;
    for (std::size_t q = 0; q < tests; ++q) work += test_cost_[slots[q]];
    probe_->packet_gap(t, Stage::kPrim, Stage::kPrimBus, *p, clock_.now());
    compute_for(t, Stage::kPrim, work, "primitive tests");
    port_.release(*p, clock_.now());
    if (j + 1 < k) ask(msg, j + ahead_, t);
  }
  // Withdraw what the search no longer needs.
  for (std::size_t e = k; e < n; ++e) {
    if (!asked_[e]) continue;
    port_.cancel(msg.leaf_shells[e].child_index, clock_.now());
    ++cancelled_;
  }
  if (res.found) compute_for(t, Stage::kPrim, tasks::kHitInfoCost, "hit info");
  // From the end of the send until the ShadeProcessor takes it, the answer is in (or, while
  // the queue is full, blocked before) queue.prim_to_shade.
  compute_for(t, Stage::kPrim, tasks::words_cost(PrimToShade::kWords), "send");
  ++split_.rays;
  blocked_until(modules::send_message(out, res, clock_.now(), PrimToShade::kWords * 4));
}

void PrimProcessor::run() {
  begin_frame();
  for (;;) {
    if (!input.fifo.has_item_by(clock_.now())) {
      idle(input.fifo.next_item_time(), input.fifo.put_event(), false);
      continue;
    }
    sc_core::sc_time taken;
    ShellToPrim msg = input.fifo.get(clock_.now(), taken);
    clock_.catch_up(taken);
    serve(msg);
  }
}

}  // namespace rtsim::platform::gaudet
