#include "platform/machines/gaudet_pert/control_processor.hpp"

#include <string>

#include "modules/activations.hpp"
#include "modules/sim_time.hpp"
#include "platform/machines/gaudet_pert/shade_processor.hpp"

namespace rtsim::platform::gaudet {

namespace {
/// Words a TLM write carries when the control processor loads a BP memory.
constexpr std::size_t kLoadBurstWords = 256;
}  // namespace

namespace {
const modules::TimeParam kLoadWordTime(
    {.name = "load_word_time",
     .default_value = "400 ns",
     .description = "Control processor: time to download one word into a BP or PERT memory "
                    "(before the frame; not part of the frame time)",
     .source = "assumption: one bus word time (L883); the thesis gives no load rate"});
}  // namespace

void ControlProcessor::declare_params(const modules::ParamDecls& control) {
  control.add(kLoadWordTime);
}

sc_core::sc_time ControlProcessor::load_word_time(const modules::ModuleParams& control) {
  return control.get(kLoadWordTime);
}

ControlProcessor::ControlProcessor(sc_core::sc_module_name name,
                                   const params::ParamRegistry& registry,
                                   std::vector<BroadcastProcessor*> buses,
                                   std::vector<const DataSetImage*> sets,
                                   std::uint64_t globals_words,
                                   std::vector<ShadeProcessor*> shade_processors)
    : sc_core::sc_module(name),
      modules::StatGroup(sc_core::sc_module::name()),
      load_word_time_(load_word_time(modules::ModuleParams(registry, this->name()))),
      buses_(std::move(buses)),
      sets_(std::move(sets)),
      globals_words_(globals_words),
      shade_(std::move(shade_processors)) {
  for (std::size_t i = 0; i < buses_.size(); ++i) {
    load_.push_back(std::make_unique<tlm_utils::simple_initiator_socket<ControlProcessor>>(
        ("load" + std::to_string(i)).c_str()));
    load_.back()->bind(buses_[i]->memory.socket);
  }
  for (ShadeProcessor* s : shade_) s->start(start_, done_);
  SC_THREAD(run);
}

void ControlProcessor::run() {
  sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
  if (!buses_.empty()) {
    // Each data set into its Broadcast Processor's memory, a burst at a time.
    for (std::size_t b = 0; b < buses_.size(); ++b) {
      const auto& mem = sets_[b]->memory;
      for (std::size_t at = 0; at < mem.size(); at += kLoadBurstWords) {
        const std::size_t n = std::min(kLoadBurstWords, mem.size() - at);
        if (!modules::write_words(*load_[b], at, &mem[at], n, delay))
          SC_REPORT_ERROR("rtsim/gaudet", "BP memory load failed");
        words_loaded_ += n;
      }
    }
  } else {
    // Direct memory: every PERT processor gets its whole data set (L806).
    std::uint64_t words = 0;
    for (const DataSetImage* s : sets_) words += s->memory.size();
    words *= shade_.size();  // every PERT
    words_loaded_ += words;
    delay = modules::plus(delay, modules::times(load_word_time_, words));
  }
  // The ray-spawn globals to every ShadeProcessor.
  const std::uint64_t g = globals_words_ * shade_.size();
  words_loaded_ += g;
  delay = modules::plus(delay, modules::times(load_word_time_, g));
  modules::sim_wait(delay);
  load_time_ = modules::sim_now();
  for (std::size_t b = 0; b < buses_.size(); ++b)
    buses_[b]->start(load_time_, sets_[b]->order.size(), sets_[b]->image.id_list_entry_words());
  start_.notify(sc_core::SC_ZERO_TIME);
  // End of frame: every ShadeProcessor has finished its scanlines.
  for (;;) {
    modules::sim_wait(done_);
    bool all = true;
    sc_core::sc_time last = load_time_;
    for (const ShadeProcessor* s : shade_) {
      all = all && s->finished();
      if (s->finished()) last = std::max(last, s->finish_time());
    }
    if (!all) continue;
    frame_time_ = last - load_time_;
    // The buses cycle on to the frame's end: their counts (and a direct-mode bus's busy time,
    // traced as it is recorded) do not stop at their last wake.
    for (BroadcastProcessor* bus : buses_) bus->run_to(last);
    sc_core::sc_stop();
    return;
  }
}

}  // namespace rtsim::platform::gaudet
