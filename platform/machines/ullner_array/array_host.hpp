#pragma once
// The host of Ullner's ray-tracing array (seed 000 L783-L797): it "maintains the scene model"
// and, after initialising the array, broadcasts it: a record for each polygon (L787), then the
// scene's other attributes, lights among them (L789), and, once the array is loaded, the viewing
// parameters that start the image (L795). Its port reaches the processor at the array's upper
// left corner, a word each host.word_time, from which the records spread through the array's
// links (broadcast_copy.hpp).
// "The host is free to perform other tasks until the array has completed the image": it takes
// no part in the frame.
//
// It waits for the array's ready line (ready_line in broadcast_copy.hpp) before the view, so
// the load, reported apart from the frame, ends when the last processor has sorted its lists.
//
// A fault in flight, `--fault host.broadcast:WORD:XOR`: word WORD of the broadcast (counted over
// every record from the first polygon's header) is XORed as it leaves the host, so every
// processor receives it corrupted.
#include <tlm_utils/simple_initiator_socket.h>

#include <cstdint>
#include <span>
#include <string>
#include <systemc>
#include <vector>

#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/machine.hpp"
#include "platform/machines/ullner_array/broadcast_copy.hpp"

namespace rtsim::platform::ullner_array {

class ArrayHost : public sc_core::sc_module, public modules::StatGroup {
 public:
  /// To the broadcast port of processor (0, 0).
  tlm_utils::simple_initiator_socket<ArrayHost> out;

  static constexpr const char* kName = "host";
  /// The fault point's name on the command line.
  static constexpr const char* kFaultPoint = "host.broadcast";
  static void declare_params(const modules::ParamDecls& host);
  /// Words the records of `scene` take in the order they are broadcast: the polygon records,
  /// the attributes, the view.
  static std::size_t attribute_words(const scenes::Scene& scene);
  static std::size_t view_words(const scenes::Camera& view);

  SC_HAS_PROCESS(ArrayHost);
  /// `faults`: those naming kFaultPoint are taken (an InputError for a word past the broadcast).
  ArrayHost(sc_core::sc_module_name name, const params::ParamRegistry& registry,
            const functional::SceneGeometry& geometry, const scenes::Scene& scene, ReadyLine& ready,
            std::vector<MemoryFault>& faults);

  /// Notified once the view has been broadcast (its timing is known by then).
  const sc_core::sc_event& loaded() const { return loaded_; }
  /// When it began to send the view: the load's end, the frame's start.
  const sc_core::sc_time& view_sent() const { return view_sent_; }
  /// stats.json: the faults in flight, [{at, word, xor_mask, applied}].
  nlohmann::ordered_json faults_json() const;

 private:
  struct Fault {
    std::uint64_t word;
    std::uint32_t xor_mask;
    std::uint64_t applied = 0;
  };
  void run();
  /// Sends `record` (a fault applied to its words) no earlier than `ready`.
  void send(std::vector<std::uint32_t> record, const sc_core::sc_time& ready);

  const functional::SceneGeometry& geometry_;
  const scenes::Scene& scene_;
  ReadyLine& ready_;
  sc_core::sc_time word_time_;  ///< host.word_time
  sc_core::sc_time port_free_ = sc_core::SC_ZERO_TIME;
  std::vector<Fault> faults_;
  std::uint64_t sent_words_ = 0;
  sc_core::sc_event loaded_;
  sc_core::sc_time view_sent_ = sc_core::SC_ZERO_TIME;

  modules::Counter records_{*this, "records", "records broadcast (polygons, attributes, view)"};
  modules::Counter words_{*this, "words", "words broadcast", modules::StatUnit::words};
  modules::Duration port_busy_{*this, "port_busy_s",
                               "time its port to processor (0, 0) carried records (the load's, "
                               "apart from the frame)"};
  modules::Computed load_time_{*this, "load_time_s", modules::StatUnit::seconds,
                               "when it began the view: the array had stored and sorted the "
                               "scene (the load, apart from the frame)",
                               [this] { return view_sent_.to_seconds(); }};
};

}  // namespace rtsim::platform::ullner_array
