#include "platform/machines/gaudet_pert/ray_probe.hpp"

namespace rtsim::platform::gaudet {

RayProbe::RayProbe(modules::LatencyProbe& probe) : probe_(probe) {
  // Named in the order a ray meets them: the probe reports them in this order.
  static constexpr const char* kNames[] = {"queue.shade_to_shell", "shell", "shell_bus",
                                           "queue.shell_to_prim",  "prim",  "prim_bus",
                                           "queue.prim_to_shade",  "shade"};
  for (int s = 0; s < 8; ++s) stage_[s] = probe_.stage(kNames[s]);
}

void RayProbe::account(RayTicket& t, Stage stage, Part part, const sc_core::sc_time& until) {
  if (until <= t.accounted_to) return;
  probe_.add(t.journey, stage_[static_cast<int>(stage)], part, until - t.accounted_to);
  t.accounted_to = until;
}

void RayProbe::shared_share(RayTicket& t, Stage proc, const sc_core::sc_time& start,
                            const sc_core::sc_time& end, std::size_t i, std::size_t k) {
  account(t, proc, Part::kQueueing, start);
  if (end <= start || k == 0) {
    account(t, proc, Part::kQueueing, end);
    return;
  }
  // Share i of k in whole time units, the shares adding up to the whole compute:
  // floor(d (i + 1) / k) - floor(d i / k).
  const auto d = (end - start).value();
  const auto share = d * (i + 1) / k - d * i / k;
  const sc_core::sc_time service = sc_core::sc_time::from_value(share);
  // The share is service wherever the cursor is; the rest of the compute is queueing.
  if (t.accounted_to < end) {
    const sc_core::sc_time left = end - t.accounted_to;
    const sc_core::sc_time s = service < left ? service : left;
    account(t, proc, Part::kService, t.accounted_to + s);
  }
  account(t, proc, Part::kQueueing, end);
}

}  // namespace rtsim::platform::gaudet
