#include "platform/machines/gaudet_pert/prim_processor.hpp"

#include "firmware/kernels/sphere.hpp"
#include "firmware/kernels/triangle.hpp"
#include "firmware/tasks/pert_task_costs.hpp"

namespace rtsim::platform::gaudet {

void PrimProcessor::declare_params(const modules::ParamDecls& prim) {
  PertProcessor::declare_params(prim, {.value = "2",
                                       .description = "ID registers of the PrimProcessor's BIC",
                                       .source = "seed 001 L910, L1056 (the PrimProcessor uses at "
                                                 "most two)"});
}

PrimProcessor::PrimProcessor(sc_core::sc_module_name name, const PertContext& c, PacketPort& port,
                             std::size_t input_depth)
    : PertProcessor(name, c.run, c.on_queue),
      input("input", input_depth, ring_queue("shell_to_prim")),
      out("out"),
      geometry_(*c.run.twin().geometry),
      record_words_(c.words),
      packet_words_(c.sets.prim.packet_words),
      test_cost_(c.test_cost),
      port_(port),
      // At most two IDs ahead (L910, L1056), and no more than it has buffers: packets come in
      // broadcast order, not t order, so with one buffer a second packet could take the only
      // buffer while the ray waits for the first, for ever.
      ahead_(std::max<std::size_t>(
          1, std::min<std::size_t>(2, params_.sub(kBic).get_count(BusInterface::kBuffers)))),
      counters_(c.run.frame().counters()) {
  start_program(program());
}

modules::Resumable PrimProcessor::ask(const ShellToPrim& msg, std::size_t k, RayTicket& t) {
  if (k >= msg.leaf_shells.size() || asked_[k]) co_return;
  co_await compute_for(t, Stage::kPrim, tasks::kAskPacketCost, "ask");
  co_await settle();
  asked_[k] = port_.request(msg.leaf_shells[k].child_index, clock_.now());
}

bool PrimProcessor::test_record(const accel::PrimRecord& rec, const Ray& ray, double t_min,
                                double t_max, SurfaceHit& out) {
  ++counters_.intersection_tests;
  if (rec.type == accel::PrimType::Sphere) {
    counters_.cost += kernels::SphereKernel::kTestCost;
    const auto k = kernels::SphereKernel::from(scenes::Sphere{rec.center, rec.radius});
    return k && k->intersect(ray, t_min, t_max, out);
  }
  counters_.cost += kernels::TriangleKernel::kTestCost;
  // The PERT's polygons are the twin's triangles (data_sets.hpp); a longer vertex list is not
  // one this PrimProcessor's firmware tests.
  if (rec.vertices.size() != 3) return false;
  const auto k =
      kernels::TriangleKernel::from(rec.vertices[0], rec.vertices[1], rec.vertices[2], nullptr);
  return k && k->intersect(ray, t_min, t_max, out);
}

modules::Resumable PrimProcessor::serve(ShellToPrim& msg) {
  PrimToShade res{msg.ticket, false, {}};
  RayTicket& t = res.ticket;  // the ray's journey goes on in the answer
  // Until now (taken) the ray waited in the input queue.
  probe_->to(t, Stage::kShellToPrim, RayProbe::Part::kQueueing, clock_.now());
  co_await compute_for(t, Stage::kPrim, tasks::words_cost(msg.words()), "ray");
  const shading::TracedRay& r = msg.ticket.ray;
  const bool light = r.kind == RayKind::Shadow;  // any hit will do (L776)
  const double t_min = msg.ticket.t_min;
  double best_t = r.t_max;
  std::int64_t best_slot = -1;
  SurfaceHit best;

  // PrimTask (Fig. 4-12) over the leaf shells the message carried, in t order, a packet at a
  // time through the BIC; `ahead_` IDs are asked for ahead of the packet being tested.
  const std::size_t n = msg.leaf_shells.size();
  asked_.assign(n, false);
  if (n > 0) ++rays_with_packets_;
  const sc_core::sc_time asked_first = clock_.now();
  for (std::size_t a = 0; a < ahead_; ++a) co_await ask(msg, a, t);
  std::size_t k = 0;  // packets tested
  for (bool done = n == 0; !done; ++k) {
    const std::size_t j = k;
    const std::uint32_t id = msg.leaf_shells[j].child_index;
    std::optional<ReceivedPacket> p;
    for (;;) {
      co_await settle();  // the packets caught by now are in
      if ((p = port_.take(clock_.now(), id))) break;
      if (!asked_[j]) {
        if (port_.register_free(clock_.now())) {
          // Till now the ray waited for an ID register.
          probe_->to(t, Stage::kPrimBus, RayProbe::Part::kQueueing, clock_.now());
          co_await ask(msg, j, t);
          continue;
        }
        // Registers free as packets arrive.
        co_await idle(port_.next_arrival(), kPort, true);
      } else {
        co_await idle(port_.next_arrival(id), kPort, true);
      }
    }
    if (j == 0) {
      first_packet_total_ += p->arrival - asked_first;
      ++first_packets_;
    }
    ++packets_;
    // The primitives are tested in packet order; a light ray stops at its first hit.
    Cost work =
        tasks::words_cost(packet_words_[id]) + tasks::kPacketBookkeepingCost + tasks::kStopTestCost;
    accel::PrimRecord rec;
    for (std::size_t at = 0; at < p->words.size();) {
      const std::size_t size = accel::decode_prim(p->words.subspan(at), record_words_, rec);
      if (size == 0) {
        ++rejected_;  // the rest of the packet cannot be read
        break;
      }
      at += size;
      if (rec.prim_id >= test_cost_.size()) {
        ++rejected_;  // no such primitive: its hit could not be reported
        continue;
      }
      const std::uint32_t slot = rec.prim_id;
      ++prim_tests_;
      work += test_cost_[slot];
      SurfaceHit s;
      if (!test_record(rec, r.ray, t_min, best_t, s)) continue;
      best_t = light ? best_t : s.t;
      best_slot = slot;
      best = s;
      if (light) break;
    }
    probe_->packet_gap(t, Stage::kPrim, Stage::kPrimBus, *p, clock_.now());
    co_await compute_for(t, Stage::kPrim, work, "primitive tests");
    co_await settle();
    port_.release(*p, clock_.now());
    // Stop rule (L646-L648): the nearest hit so far is closer than the next leaf shell.
    done = j + 1 == n || (best_slot >= 0 && (light || best_t < msg.leaf_shells[j + 1].t));
    if (!done) co_await ask(msg, j + ahead_, t);
  }
  res.found = best_slot >= 0;
  if (res.found) {
    // Hit info (point, normals): the record gave t and the geometric normal; the vertex
    // normals are the host's (not in the records), so the shading normal comes from its copy of
    // the primitive when that copy hits at the same t -- always, unless a word was corrupted.
    const auto slot = static_cast<std::uint32_t>(best_slot);
    SurfaceHit host;
    TraceCounters uncounted;
    if (functional::test_shape(geometry_, slot, r.ray, t_min, kInfinity, host, uncounted) &&
        host.t == best.t)
      best = host;
    functional::fill_hit(geometry_, slot, best, res.hit);
    if (!light) ++counters_.hits;
  }
  // Withdraw what the search no longer needs.
  for (std::size_t e = k; e < n; ++e) {
    if (!asked_[e]) continue;
    co_await settle();
    port_.cancel(msg.leaf_shells[e].child_index, clock_.now());
    ++cancelled_;
  }
  if (res.found) co_await compute_for(t, Stage::kPrim, tasks::kHitInfoCost, "hit info");
  // From the end of the send until the ShadeProcessor takes it, the answer is in (or, while
  // the queue is full, blocked before) queue.prim_to_shade.
  const WritingAhead ahead(*this);
  const sc_core::sc_time since = clock_.now();
  co_await compute_for(t, Stage::kPrim, tasks::words_cost(PrimToShade::kWords), "send");
  ++rays_;
  const sc_core::sc_time arrival = over_link(PrimToShade::kWords, since, t);
  // A put into a full queue waits for a take (TimedFifo::put).
  while (out_queue_->full()) co_await room();
  // Blocked until the queue took it, less its flight on the link.
  co_await blocked_until(
      modules::send_message(out, res, arrival, std::uint64_t{32} * PrimToShade::kWords) -
      link_latency());
}

modules::Resumable PrimProcessor::program() {
  co_await begin_frame();
  for (;;) {
    co_await settle();
    if (!input.fifo.has_item_by(clock_.now())) {
      co_await idle(input.fifo.next_item_time(), kInput, false);
      continue;
    }
    sc_core::sc_time taken;
    ShellToPrim msg = input.fifo.get(clock_.now(), taken);
    co_await catch_up(taken);
    co_await serve(msg);
  }
}

}  // namespace rtsim::platform::gaudet
