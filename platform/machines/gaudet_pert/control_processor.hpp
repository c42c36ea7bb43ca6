#pragma once
// Gaudet's control processor (seed 001 §5.5, L928): it preprocesses the scene (done before
// the simulation, data_sets.hpp), downloads each data set into its Broadcast Processor's memory
// (or, for the direct-memory baseline, into every PERT processor's memory), downloads the
// globals the ShadeProcessors need to spawn rays (camera, lights), starts the frame and detects
// its end: every ShadeProcessor has finished its scanlines.
#include <tlm_utils/simple_initiator_socket.h>

#include <memory>
#include <vector>

#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "platform/machines/gaudet_pert/broadcast_processor.hpp"
#include "platform/machines/gaudet_pert/data_sets.hpp"

namespace rtsim::platform::gaudet {

class ShadeProcessor;

class ControlProcessor : public sc_core::sc_module, public modules::StatGroup {
 public:
  /// Its parameters under `control`: the download rate.
  static void declare_params(const modules::ParamDecls& control);
  /// Its download rate, which the memories it loads are timed by (read before it is built).
  static sc_core::sc_time load_word_time(const modules::ModuleParams& control);

  SC_HAS_PROCESS(ControlProcessor);
  /// `buses`: the Shade, Shell and Prim broadcasters (empty for the direct-memory baseline);
  /// `sets` the matching images; `globals_words` what each ShadeProcessor is sent.
  ControlProcessor(sc_core::sc_module_name name, const params::ParamRegistry& registry,
                   std::vector<BroadcastProcessor*> buses, std::vector<const DataSetImage*> sets,
                   std::uint64_t globals_words, std::vector<ShadeProcessor*> shade_processors);

  /// Notified when the frame starts (after the downloads).
  const sc_core::sc_event& frame_start() const { return start_; }
  sc_core::sc_time load_time() const { return load_time_; }
  sc_core::sc_time frame_time() const { return frame_time_; }

 private:
  void run();

  sc_core::sc_time load_word_time_;
  std::vector<BroadcastProcessor*> buses_;
  std::vector<const DataSetImage*> sets_;
  std::uint64_t globals_words_;
  std::vector<ShadeProcessor*> shade_;
  std::vector<std::unique_ptr<tlm_utils::simple_initiator_socket<ControlProcessor>>> load_;
  sc_core::sc_event start_;
  sc_core::sc_event done_;
  sc_core::sc_time load_time_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time frame_time_ = sc_core::SC_ZERO_TIME;
  modules::Counter words_loaded_{*this, "words_loaded",
                                 "words downloaded into the buses' and the PERTs' memories",
                                 modules::StatUnit::words};
};

}  // namespace rtsim::platform::gaudet
