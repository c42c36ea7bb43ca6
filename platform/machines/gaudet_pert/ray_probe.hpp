#pragma once
// `--latency-probe` on gaudet-pert: where a ray's time goes on its way around its PERT's ring,
// from the moment the ShadeProcessor has sent it to the moment it has taken in the answer (the
// window of stats.json `ray_latency_s`).
//
// The stages, in the order a ray meets them (aggregated over the PERTs):
//   queue.shade_to_shell, shell, shell_bus, queue.shell_to_prim, prim, prim_bus,
//   queue.prim_to_shade, shade
// (a SHADE packet is asked for only after the window closes: no shade_bus stage).
//
// Attribution, exact by construction: every ray carries a cursor, the time up to which its
// journey is accounted. Each attribution covers [cursor, until) and moves the cursor to
// `until`; pieces that lie before the cursor are clipped away, so the pieces tile the window
// and nothing is counted twice (a ray with several packets outstanding, a packet several rays
// share). The processors call, whenever they start work for a ray at `start`:
//   * gap before a packet's work: bus queueing until the packet's transfer started (waiting
//     for an ID register or the packet's slot in the broadcast cycle), bus transfer until its
//     last word was in the buffer, then queueing at the processor (busy with other rays);
//   * gap before other work: queueing at the processor, or bus queueing when the ray waited
//     for an ID register (a re-asked ID), or queueing at the next queue while it was full;
//   * the work itself: service at the processor; a compute done once for k rays (reading a
//     packet several rays wait for, re-asking an ID) is split: each ray gets 1/k of it as
//     service and the rest as queueing, so the service summed over rays is the processor's
//     processing time.
// Time in an input queue (put to taken, including a sender blocked on a full queue) is queueing
// at that queue: the message links have no transfer time of their own.
//
// Disabled, a ray's journey is LatencyProbe::kNoJourney and every call is one branch.
#include <cstddef>
#include <systemc>

#include "modules/latency_probe.hpp"
#include "platform/machines/gaudet_pert/messages.hpp"
#include "platform/machines/gaudet_pert/packet_port.hpp"

namespace rtsim::platform::gaudet {

enum class Stage : int {
  kShadeToShell = 0,
  kShell,
  kShellBus,
  kShellToPrim,
  kPrim,
  kPrimBus,
  kPrimToShade,
  kShade,
};

class RayProbe {
 public:
  using Part = modules::LatencyPart;

  /// Names the ring's stages in `probe` (the run's --latency-probe; first, so they come first).
  explicit RayProbe(modules::LatencyProbe& probe);

  modules::LatencyProbe& probe() { return probe_; }
  const modules::LatencyProbe& probe() const { return probe_; }

  /// The ray has been sent at `now`: its journey starts.
  void begin(RayTicket& t, const sc_core::sc_time& now) {
    if (!probe_.enabled()) return;
    t.journey = probe_.begin(now);
    t.accounted_to = now;
  }
  /// The answer has been taken in at `now` (the cursor is there): the journey ends.
  void end(RayTicket& t, const sc_core::sc_time& now) {
    if (t.journey == modules::LatencyProbe::kNoJourney) return;
    probe_.end(t.journey, now);
    t.journey = modules::LatencyProbe::kNoJourney;
  }

  /// Attributes [cursor, until) to `part` at `stage` and moves the cursor to `until` (nothing
  /// if `until` is not after the cursor).
  void to(RayTicket& t, Stage stage, Part part, const sc_core::sc_time& until) {
    if (t.journey == modules::LatencyProbe::kNoJourney) return;
    account(t, stage, part, until);
  }

  /// The gap before work on packet `p` starting at `start`: queueing at `bus` until the
  /// packet's transfer started, transfer at `bus` until it arrived, then queueing at `proc`.
  void packet_gap(RayTicket& t, Stage proc, Stage bus, const ReceivedPacket& p,
                  const sc_core::sc_time& start) {
    if (t.journey == modules::LatencyProbe::kNoJourney) return;
    account(t, bus, Part::kQueueing, p.transfer_start);
    // A streamed packet is taken before its last word is in: its transfer counts until then.
    account(t, bus, Part::kTransfer, p.arrival < start ? p.arrival : start);
    account(t, proc, Part::kQueueing, start);
  }

  /// Share `i` of `k` of a compute [start, end) done once for k rays: the gap before it is
  /// queueing at `proc` (the caller attributes it first if it was something else), then
  /// 1/k of it is service, the rest queueing at `proc`.
  void shared(RayTicket& t, Stage proc, const sc_core::sc_time& start, const sc_core::sc_time& end,
              std::size_t i, std::size_t k) {
    if (t.journey == modules::LatencyProbe::kNoJourney) return;
    shared_share(t, proc, start, end, i, k);
  }

 private:
  void account(RayTicket& t, Stage stage, Part part, const sc_core::sc_time& until);
  void shared_share(RayTicket& t, Stage proc, const sc_core::sc_time& start,
                    const sc_core::sc_time& end, std::size_t i, std::size_t k);

  modules::LatencyProbe& probe_;
  int stage_[8];  ///< LatencyProbe stage index of each Stage
};

}  // namespace rtsim::platform::gaudet
