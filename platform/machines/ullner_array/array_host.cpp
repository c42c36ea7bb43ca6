#include "platform/machines/ullner_array/array_host.hpp"

#include "common/input_error.hpp"
#include "modules/sim_time.hpp"
#include "platform/machines/ullner_array/broadcast_record.hpp"

namespace rtsim::platform::ullner_array {

namespace {
const modules::TimeParam kWordTime(
    {.name = "word_time",
     .default_value = "1 us",
     .description = "Time for the host's port to deliver one 32-bit word of the broadcast to "
                    "processor (0, 0)",
     .source = "assumption: the thesis gives no host interface (L785); a word a microsecond, a "
               "DMA channel of 1982"});
}  // namespace

void ArrayHost::declare_params(const modules::ParamDecls& host) { host.add(kWordTime); }

std::size_t ArrayHost::attribute_words(const scenes::Scene& scene) {
  return attributes_record(scene).size();
}

std::size_t ArrayHost::view_words(const scenes::Camera& view) { return view_record(view).size(); }

ArrayHost::ArrayHost(sc_core::sc_module_name name, const params::ParamRegistry& registry,
                     const functional::SceneGeometry& geometry, const scenes::Scene& scene,
                     ReadyLine& ready, std::vector<MemoryFault>& faults)
    : sc_core::sc_module(name),
      modules::StatGroup(sc_core::sc_module::name()),
      out("out"),
      geometry_(geometry),
      scene_(scene),
      ready_(ready),
      word_time_(modules::ModuleParams(registry, kName).get(kWordTime)) {
  std::uint64_t total = attribute_words(scene) + view_words(scene.camera);
  for (const auto& s : geometry.shapes)
    total += polygon_record_words(std::get<kernels::UllnerQuadKernel>(s.shape).has_corner_normals);
  for (const MemoryFault& f : faults) {
    if (f.memory != kFaultPoint) continue;
    if (f.word >= total)
      throw InputError("--fault " + f.memory + ":" + std::to_string(f.word), 0,
                       "the host broadcasts " + std::to_string(total) +
                           " words on this scene (0 to " + std::to_string(total - 1) + ")");
    faults_.push_back({f.word, f.xor_mask});
  }
  std::erase_if(faults, [](const MemoryFault& f) { return f.memory == kFaultPoint; });
  SC_THREAD(run);
}

void ArrayHost::run() {
  // Every record is offered as soon as the port is free; the array's processors pace it.
  for (std::size_t slot = 0; slot < geometry_.shapes.size(); ++slot)
    send(polygon_record(geometry_, static_cast<std::uint32_t>(slot)), sc_core::SC_ZERO_TIME);
  send(attributes_record(scene_), sc_core::SC_ZERO_TIME);
  // The view once every processor has raised its ready flag (L795).
  view_sent_ = std::max(port_free_, ready_.at);
  send(view_record(scene_.camera), view_sent_);
  loaded_.notify(sc_core::SC_ZERO_TIME);
}

void ArrayHost::send(std::vector<std::uint32_t> record, const sc_core::sc_time& ready) {
  for (auto& f : faults_) {
    if (f.word < sent_words_ || f.word >= sent_words_ + record.size()) continue;
    record[f.word - sent_words_] ^= f.xor_mask;
    ++f.applied;
  }
  sent_words_ += record.size();
  const sc_core::sc_time duration = modules::times(word_time_, record.size());
  const sc_core::sc_time start = offer_record(out, record, std::max(ready, port_free_), duration);
  port_free_ = modules::plus(start, duration);
  port_busy_ += duration;
  ++records_;
  words_ += record.size();
}

nlohmann::ordered_json ArrayHost::faults_json() const {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& f : faults_)
    out.push_back(
        {{"at", kFaultPoint}, {"word", f.word}, {"xor_mask", f.xor_mask}, {"applied", f.applied}});
  return out;
}

}  // namespace rtsim::platform::ullner_array
