#pragma once
// The ShellProcessor of a PERT (seed 001 §4.5, Fig. 4-10, L752-L757; §5.4.1, L910): takes
// SHADE_TO_SHELL rays, searches the shell hierarchy with the SHELL packets its BIC catches off
// the Shell bus, and sends each ray's sorted LeafShellList on as SHELL_TO_PRIM.
//
// Per ray: ask for packet 0 (the root's children, L662), or, with `root_local`, read it from its
// own memory, which holds the globals (L863); box-test the SHELLs of every packet as
// it arrives — in broadcast order, not request order — adding hit leaf shells to the list and
// asking for the children packet of every hit parent; when no packet is outstanding, sort the
// list (L734) and send it. The processor keeps up to `rays_in_flight` rays at a time and stores
// IDs "continually": when no ID register is free it stacks the ID in its own memory until one
// is (L910). A packet several rays wait for is caught once and tested for each of them.
//
// With the BIC's `stream` set (L920, L924) a packet is taken once its first SHELL record is in
// and SHELL k is tested once its words are in, while the rest streams into the FIFO; the wait
// for a record is latency (the processor is committed to the packet).
//
// The SHELLs tested are the records in the packet's words as the BIC received them
// (accel::decode_shell): a word corrupted in the Shell bus's memory changes the search. A
// record that points outside the data sets (a child or PRIM packet that does not exist) is
// dropped and counted, so a corrupted memory cannot hang the machine.
#include <tlm_utils/simple_initiator_socket.h>

#include <algorithm>
#include <deque>
#include <span>
#include <vector>

#include "firmware/accel/shell_traversal.hpp"
#include "modules/message_channel.hpp"
#include "platform/machines/gaudet_pert/messages.hpp"
#include "platform/machines/gaudet_pert/packet_port.hpp"
#include "platform/machines/gaudet_pert/pert_context.hpp"
#include "platform/machines/gaudet_pert/pert_processor.hpp"

namespace rtsim::platform::gaudet {

class ShellProcessor : public PertProcessor {
 public:
  modules::MessageQueue<ShadeToShell> input;
  tlm_utils::simple_initiator_socket<ShellProcessor> out;

  /// `tree`: what the control processor knows of the data sets (how many SHELL and PRIM
  /// packets there are); `record_words`: words per SHELL record.
  /// `root_packet`: packet 0's words, copied into its local memory if `root_local` is set.
  /// Its data set (the SHELL packets, their shell tree and record size) from `context`, read
  /// through `port`; its input queue `input_depth` messages deep.
  ShellProcessor(sc_core::sc_module_name name, const PertContext& context, PacketPort& port,
                 std::size_t input_depth);
  /// Its parameters under `shell` ("pert.shell").
  static void declare_params(const modules::ParamDecls& shell);
  /// Words of a SHELL record as it reads them, from the data sets' `data.words.shell`.
  static std::uint32_t record_words(std::uint32_t shell_words) {
    return std::max<std::uint32_t>(shell_words, 8);
  }

  /// Elaboration: the queue `out` feeds (to see whether it has room).
  void set_output_queue(const modules::TimedFifo<ShellToPrim>& q) { out_queue_ = &q; }

 private:
  struct Search {
    RayTicket ticket;
    Vec3 inv_dir;
    std::vector<accel::LeafShellEntry> leaves;
    int outstanding = 0;  ///< packets asked for and not yet tested
    bool active = false;
  };
  /// Its loop (PertProcessor::start_program): sends finished lists, reads packets, asks for
  /// stacked IDs, takes rays.
  modules::Resumable program();
  modules::Resumable begin(ShadeToShell msg);
  modules::Resumable process(const ReceivedPacket& p);
  /// Reads packet `p` (its words, one cycle each) and box-tests its SHELLs for `rays`.
  modules::Resumable read_and_test(const ReceivedPacket& p, const std::vector<int>* rays);
  modules::Resumable ask(std::uint32_t packet, int search);
  modules::Resumable finish(int search);

  const accel::ShellTree& tree_;
  const std::vector<std::uint32_t>& packet_words_;
  std::uint32_t record_words_;
  std::vector<std::uint32_t> local_root_;  ///< packet 0 in its local memory (root_local)
  bool root_local_ = false;
  PacketPort& port_;
  TraceCounters& counters_;
  const modules::TimedFifo<ShellToPrim>* out_queue_ = nullptr;

  std::vector<Search> searches_;
  /// Packet ID -> the searches waiting for it (none: empty), by ID. A packet asked for and caught
  /// again and again reuses its list: a map's node and list were allocated and freed for each.
  std::vector<std::vector<int>> waiting_;
  std::size_t packets_awaited_ = 0;      ///< IDs of waiting_ whose list is not empty
  std::vector<int> caught_for_;          ///< the list of the packet being read, out of waiting_
  std::vector<std::uint32_t> overflow_;  ///< IDs stacked in memory, no register free (L910)
  std::deque<int> done_;                 ///< searches whose list is ready to send
  std::vector<std::uint32_t> children_;
  /// The records of the packet being processed, each with the words it ends at (a streamed
  /// packet's record is tested once its words are in).
  std::vector<std::pair<accel::Shell, std::size_t>> shells_;
  modules::Counter box_tests_{*this, "box_tests", "SHELL boxes tested against a ray"};
  modules::Counter packets_{*this, "packets_caught", "packets read off the bus (or its memory)"};
  modules::Counter packet_uses_{*this, "packet_uses",
                                "packets read for a ray (a packet caught "
                                "once may serve several)"};
  modules::Peak overflow_peak_{*this, "overflow_peak",
                               "IDs stacked in its memory with no ID register free (L910)"};
  modules::Counter leaf_shells_{*this, "leaf_shells", "leaf shells listed for the rays"};
  modules::Counter over_capacity_{*this, "rays_over_list_capacity",
                                  "rays with more leaf shells than the list to Prim holds"};
  modules::Counter rejected_{*this, "records_rejected",
                             "SHELL records dropped because they point at no packet (only with "
                             "corrupted memories), once per packet caught"};
};

}  // namespace rtsim::platform::gaudet
