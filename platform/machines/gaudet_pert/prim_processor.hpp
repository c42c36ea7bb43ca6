#pragma once
// The PrimProcessor of a PERT (seed 001 §4.5, Fig. 4-12, L771-L786; §6.3, L1053-L1062): takes
// SHELL_TO_PRIM rays and tests the primitives of their leaf shells strictly in t order, a PRIM
// packet at a time, with the packets its BIC catches off the Prim bus.
//
// One ray at a time, at most two packet IDs in the BIC (L910, L1056): it asks for the first
// two leaf shells, and after testing packet j, if the search goes on, for leaf shell j + 2. It
// stops when the nearest primitive hit is closer than the next leaf shell (L646-L648), or for a
// light ray at the first hit (L776), and withdraws the request it no longer needs. Then it
// computes the point and normal and sends PRIM_TO_SHADE.
//
// The answer is the processor's own: it runs PrimTask (accel/shell_traversal.hpp's rules) over
// the LeafShellList the SHELL_TO_PRIM message carried, so what the ShellProcessor found -- from
// the SHELL records in its packets -- decides what is tested; the machine's twin only checks
// the image afterwards. The primitives it tests are the PRIM records in the packet's words as
// its BIC received them (accel::decode_prim: spheres, and triangles as 3-vertex polygons, in
// singles); the twin holds the same rounded primitives (RenderSettings::prims_as_stored). It
// charges its own firmware's tests for the primitives it tested (tasks::kPertSphereTestCost,
// kPertTriangleTestCost). A record it cannot read, or that names no primitive, is dropped and
// counted (records_rejected: only with a corrupted memory).
#include <tlm_utils/simple_initiator_socket.h>

#include <vector>

#include "firmware/accel/gaudet_data_sets.hpp"
#include "modules/message_channel.hpp"
#include "platform/functional/scene_tracer.hpp"
#include "platform/machines/gaudet_pert/messages.hpp"
#include "platform/machines/gaudet_pert/packet_port.hpp"
#include "platform/machines/gaudet_pert/pert_context.hpp"
#include "platform/machines/gaudet_pert/pert_processor.hpp"

namespace rtsim::platform::gaudet {

class PrimProcessor : public PertProcessor {
 public:
  modules::MessageQueue<ShellToPrim> input;
  tlm_utils::simple_initiator_socket<PrimProcessor> out;

  /// `geometry`: the host's copy of the primitives (slot numbers, materials, vertex normals);
  /// `record_words`: the PRIM records' sizes.
  /// Its data set (the PRIM packets, the record sizes, each shape's test cost) from `context`
  /// and the twin's geometry (the host's copy, for reporting hits), read through `port`; its
  /// input queue `input_depth` messages deep.
  PrimProcessor(sc_core::sc_module_name name, const PertContext& context, PacketPort& port,
                std::size_t input_depth);
  /// Its parameters under `prim` ("pert.prim").
  static void declare_params(const modules::ParamDecls& prim);
  /// Elaboration: the queue `out` feeds (a put into it waits while it is full).
  void set_output_queue(const modules::TimedFifo<PrimToShade>& q) { out_queue_ = &q; }

 private:
  /// Its loop (PertProcessor::start_program): takes a ray's list and serves it.
  modules::Resumable program();
  modules::Resumable serve(ShellToPrim& msg);
  /// Asks for leaf shell `k` of the list (for ray `t`, --latency-probe); keeps it for later if
  /// no register is free.
  modules::Resumable ask(const ShellToPrim& msg, std::size_t k, RayTicket& t);
  /// The firmware's test of one decoded primitive (counted in counters_).
  bool test_record(const accel::PrimRecord& rec, const Ray& ray, double t_min, double t_max,
                   SurfaceHit& out);

  const functional::SceneGeometry& geometry_;
  accel::RecordWords record_words_;
  const std::vector<std::uint32_t>& packet_words_;
  const std::vector<Cost>& test_cost_;  ///< by primitive slot: the PERT's own test
  PacketPort& port_;
  std::size_t ahead_;  ///< IDs asked for ahead of the packet being tested
  TraceCounters& counters_;
  const modules::TimedFifo<PrimToShade>* out_queue_ = nullptr;

  std::vector<bool> asked_;  ///< per list entry of the current ray
  modules::Counter packets_{*this, "packets_caught", "packets read off the bus (or its memory)"};
  modules::Counter cancelled_{*this, "packets_cancelled",
                              "packets asked for and no longer needed (the ray's hit is nearer)"};
  modules::Counter prim_tests_{*this, "prim_tests", "primitives tested against a ray"};
  modules::Counter rays_with_packets_{*this, "rays_with_packets",
                                      "rays that needed at least one packet"};
  modules::Counter rejected_{*this, "records_rejected",
                             "PRIM records dropped: unreadable, or naming no primitive (only "
                             "with corrupted memories)"};
  modules::Duration first_packet_total_{
      *this, "first_packet_latency_total_s",
      "from asking for a ray's first packet to having it (L1060-L1062), summed over rays"};
  modules::Counter first_packets_{*this, "first_packets", "rays whose first packet came"};
};

}  // namespace rtsim::platform::gaudet
