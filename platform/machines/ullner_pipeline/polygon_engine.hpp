#pragma once
// One polygon processor of the chain as a module (`pipeline.model = engines`; seed 000 L690-L713,
// Fig. 2-23): the ray description reaches it as a TLM transaction on its input socket, it
// intersects the ray with the polygon its registers hold, overwrites the intersection fields if
// that hit is closer than the carried t (writing the identity word loaded with its polygon), and
// passes the description on through its output socket over its bit-serial link.
//
// Its timing is its own state's (the rules of chain_timing.hpp, one processor at a time):
//     accepts     E(j) = max(A(j), E(j-1) + issue_interval, S(j-1))   A: arrival in its register;
//                                                                      it holds one description
//     ready       R(j) = E(j) + hop_latency
//     link starts S(j) = max(R(j), S(j-1) + serialisation, next's E(j-1) - link latency)
//     arrives     A'(j) = S(j) + serialisation + link latency        at the next processor
// The next processor's input register is free once it has accepted the previous description,
// and must be by the time the first bit reaches it: the handshake (L729-L731) is that
// processor's E(j-1), read through `next`. The last processor's next register is a slot of the
// host's result queue, which the chain gives it (set_far_end_room). The chain's thread carries
// each description from one processor to the next as far as the one ahead of it allows
// (loosely timed: no processor waits in simulated time; the times travel in the description,
// DescriptionInFlight::at).
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include <cstdint>
#include <systemc>
#include <tlm>
#include <vector>

#include "firmware/kernels/ullner_quad.hpp"
#include "modules/busy_timeline.hpp"
#include "modules/chain_hop.hpp"
#include "modules/link.hpp"
#include "platform/machines/ullner_pipeline/chain_timing.hpp"
#include "platform/machines/ullner_pipeline/description_fault.hpp"
#include "platform/machines/ullner_pipeline/polygon_load.hpp"

namespace rtsim::platform::ullner_pipeline {

/// The polygons the processors' registers hold, decoded (the chain's register file): processor k
/// tests polygon[k] and writes identity[k].
struct HeldPolygons {
  const std::vector<kernels::UllnerQuadParams<double>>* polygon = nullptr;
  const std::vector<std::uint32_t>* identity = nullptr;
  /// Per processor: descriptions it overwrote (the chain's class statistics).
  std::vector<std::uint64_t>* overwrites = nullptr;
};

/// `in`: from the previous processor (or the host's end); `out`: to the next (or the chain's
/// far end).
class PolygonEngine : public modules::ChainHop {
 public:
  /// The load (L717-L719): a polygon description from the previous processor (or the host's
  /// end), and this one's previous polygon on to the next (or back to the host).
  tlm_utils::simple_target_socket<PolygonEngine> load_in;
  tlm_utils::simple_initiator_socket<PolygonEngine> load_out;

  /// Processor `index` with `timing`; its output link carries a description in `serialisation`
  /// and delivers it `link_latency` later.
  PolygonEngine(const sc_core::sc_module_name& name, std::uint64_t index,
                const EngineTiming& timing, const sc_core::sc_time& serialisation,
                const sc_core::sc_time& link_latency, const HeldPolygons& held);

  /// Faults: `fault` corrupts every description entering it; a dead processor passes every
  /// description on unchanged.
  void add_fault(DescriptionFault& fault) { faults_.push_back(&fault); }
  void set_dead(bool dead) { dead_ = dead; }
  /// Records its issue slots (one issue interval from each acceptance) in `timeline`: when it
  /// was busy, for fill and drain along the chain.
  void watch(modules::BusyTimeline* timeline) { timeline_ = timeline; }

  /// The processor after this one (its handshake), at elaboration; none for the last.
  void set_next(const PolygonEngine* next) { next_ = next; }
  /// When its input register was last freed (it accepted a description then).
  const sc_core::sc_time& register_free() const { return last_accept_; }
  /// The earliest it accepts its next description: an issue interval after the last, and once
  /// it has started passing the last on (zero before the first).
  sc_core::sc_time accept_bound() const;
  /// The last processor: its link must not start before this (a slot of the host's result
  /// queue is free then).
  void set_far_end_room(const sc_core::sc_time& t) { far_end_room_ = t; }
  /// Starts passing on the description it has computed (ready at its `at`) over its link: needs
  /// the next processor's handshake (it has accepted the previous description). `at` becomes
  /// when the description is in the next register, or for the last when its link starts.
  void start(tlm::tlm_generic_payload& gp);
  /// Hands it to the next processor, which accepts and computes it (needs that one to have
  /// started passing on the previous description), or to the chain's far end.
  void hand_on(tlm::tlm_generic_payload& gp);
  /// The load: its registers are `registers`' line `index`; a description takes `polygon_time`
  /// on its link.
  void hold_registers(RegisterFile* registers, const sc_core::sc_time& polygon_time) {
    registers_ = registers;
    polygon_time_ = polygon_time;
  }
  /// Passes the load's wave (its previous polygon, after load_in) on through load_out.
  void shift_on(tlm::tlm_generic_payload& gp);

  /// When it first and last accepted a description (fill and drain along the chain).
  const sc_core::sc_time& first_accept() const { return first_accept_; }
  const sc_core::sc_time& last_accept() const { return last_accept_; }
  /// Time descriptions waited, ready, for its link or the next register.
  const sc_core::sc_time& waited() const { return waited_; }
  /// The last processor: time descriptions waited for a result slot alone.
  const sc_core::sc_time& far_end_held() const { return far_end_held_; }

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) override;
  void load_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);

  std::uint64_t index_;
  EngineTiming timing_;
  sc_core::sc_time serialisation_, link_latency_;
  HeldPolygons held_;
  const PolygonEngine* next_ = nullptr;
  std::vector<DescriptionFault*> faults_;
  modules::BusyTimeline* timeline_ = nullptr;
  RegisterFile* registers_ = nullptr;
  sc_core::sc_time polygon_time_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time load_link_free_ = sc_core::SC_ZERO_TIME;
  bool dead_ = false;
  bool any_ = false;
  sc_core::sc_time first_accept_ = sc_core::SC_ZERO_TIME, last_accept_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time last_start_ = sc_core::SC_ZERO_TIME;  ///< S(j-1)
  sc_core::sc_time link_free_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time far_end_room_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time waited_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time far_end_held_ = sc_core::SC_ZERO_TIME;
};

}  // namespace rtsim::platform::ullner_pipeline
