#include "platform/machines/ullner_pipeline/pipeline_host.hpp"

#include <algorithm>
#include <span>

#include "modules/extension_guard.hpp"
#include "modules/message_channel.hpp"
#include "modules/sim_time.hpp"
#include "platform/functional/scene_geometry.hpp"

namespace rtsim::platform::ullner_pipeline {

namespace {

// The pipeline host's own parameters (host.*), each named once.
const modules::CountParam kRaysInFlight(
    {.name = "rays_in_flight",
     .default_value = "16384",
     .min = "1",
     .max = "1000000",
     .unit = "rays",
     .description = "Rays the host has sent and not yet had answered, at most: it must \"pursue "
                    "many successive ray tracing computations at once\"; each has a slot reserved "
                    "for its answer, so the chain never waits for the host to read one",
     .source = "seed 000 L715; assumption: enough for 10,000 processors (L751), each holding one "
               "description, plus the result fields' lag"});
const modules::CountParam kResultSlots(
    {.name = "result_slots",
     .default_value = "0",
     .min = "0",
     .max = "1000000",
     .unit = "answers",
     .description = "Answers the host's end of the chain can hold until the host takes them; 0 "
                    "for one per ray in flight (the chain never waits). Fewer make a host slow "
                    "to take its answers hold up the last processor, and through it the chain: "
                    "the thesis's \"so long as the pipe is kept full\" becomes a condition the "
                    "run measures (pipeline.kept_full)",
     .source = "seed 000 L743, L745 (a host that cannot \"deal with the responses\" as fast); "
               "the thesis gives no size: a what-if"});
const modules::FlagParam kAnswersFirst(
    {.name = "answers_first",
     .default_value = "true",
     .description = "The host takes a waiting answer before it makes or sends a ray, as the "
                    "thesis orders its two tasks; false: it sends whenever the chain's first "
                    "register is free and takes answers only when it cannot (a host that floods "
                    "the chain, whose answers then back up from the far end: with few "
                    "host.result_slots, up to the first processor)",
     .source = "seed 000 L474-L476 (task 2 whenever a result is waiting, task 1 otherwise); "
               "false is a what-if"});
const modules::RealParam kDummyDistance(
    {.name = "dummy_distance",
     .default_value = "1e6",
     .min = "2",
     .max = "1e12",
     .unit = "extents",
     .description = "Where the dummy polygons of spare processors lie: this many modelling-space "
                    "extents from its centre (along +z), so every real polygon a ray meets is "
                    "closer than a dummy",
     .source = "seed 000 L719 (\"very far away from the scene model\"); assumption: far beyond "
               "any eye or light a scene places"});

}  // namespace

void PipelineHost::declare_params(const modules::ParamDecls& host) {
  Host::declare_processor_params(host);
  host.add(kRaysInFlight);
  host.add(kResultSlots);
  host.add(kAnswersFirst);
  host.add(kDummyDistance);
}

std::uint64_t PipelineHost::rays_in_flight(const modules::ModuleParams& host) {
  return host.get(kRaysInFlight);
}

bool PipelineHost::answers_first(const modules::ModuleParams& host) {
  return host.get(kAnswersFirst);
}

std::uint64_t PipelineHost::result_slots(const modules::ModuleParams& host) {
  const std::uint64_t slots = host.get(kResultSlots);
  return slots == 0 ? 0 : std::min(slots, host.get(kRaysInFlight));
}

PipelineHost::PipelineHost(sc_core::sc_module_name name, MachineRun& run,
                           const ullner::HostAttachment& attached, std::uint64_t engines,
                           const Bounds& modelling_space)
    : Host(name, run, attached),
      engines_(engines),
      modelling_space_(modelling_space),
      dummy_distance_(modules::ModuleParams(run.registry(), this->name()).get(kDummyDistance)) {}

kernels::UllnerQuadParams<double> PipelineHost::dummy(const Bounds& space, double distance) {
  const double e = functional::scene_extent(space);
  const Vec3 c = space.center() + Vec3(0.0, 0.0, distance * e);
  const double h = 0.5 * e;
  const auto quad = kernels::UllnerQuadKernel::from(c + Vec3(-h, -h, 0.0), c + Vec3(h, -h, 0.0),
                                                    c + Vec3(h, h, 0.0), c + Vec3(-h, h, 0.0));
  return quad->params;
}

void PipelineHost::load_scene() {
  // N presentations: the last one rests in the first processor, so the host presents the
  // dummies of the spare processors first (they end at the far end) and polygon 0 last; the
  // j-th rests in processor N-1-j with identity N-1-j. Formatting a description is the host's
  // (its words written); the load is timed apart from the frame, so it is not counted as the
  // frame's busy time or link traffic.
  const std::uint64_t polygons = geometry_.shapes.size();
  PolygonLoad msg;
  modules::MessageExtension<PolygonLoad> ext(&msg);
  tlm::tlm_generic_payload gp;
  gp.set_command(tlm::TLM_WRITE_COMMAND);
  gp.set_address(0);
  gp.set_data_ptr(nullptr);
  gp.set_data_length(PolygonDescription::kWords * 4);
  gp.set_streaming_width(PolygonDescription::kWords * 4);
  gp.set_byte_enable_ptr(nullptr);
  gp.set_extension(&ext);
  const modules::ClearExtensionOnExit<modules::MessageExtension<PolygonLoad>> clear(gp, ext);
  const sc_core::sc_time format =
      timing().time_for(Cost{.mem_words = PolygonDescription::kWords, .instructions = 4});
  const sc_core::sc_time on_link = link_to_machine().serialisation(PolygonDescription::kWireBits);
  sc_core::sc_time all_back = clock_.now();
  const kernels::UllnerQuadParams<double> dummy_params = dummy(modelling_space_, dummy_distance_);
  for (std::uint64_t j = 0; j < engines_; ++j) {
    const std::uint64_t slot = engines_ - 1 - j;
    const auto& params =
        slot >= polygons ? dummy_params
                         : std::get<kernels::UllnerQuadKernel>(geometry_.shapes[slot].shape).params;
    kernels::describe(params, static_cast<std::uint32_t>(slot), msg.presented.words);
    clock_.advance(format);
    const sc_core::sc_time arrived = modules::plus(clock_.now(), on_link);
    sc_core::sc_time delay = arrived - modules::sim_now();
    gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    load_out->b_transport(gp, delay);
    if (gp.is_response_error()) SC_REPORT_ERROR("rtsim/ullner-pipeline", "polygon load failed");
    // Held until the first processor accepted it (its input register is free again).
    clock_.catch_up(modules::sim_now() + delay);
    all_back = std::max(all_back, msg.returned_at);
    ++returned_;
  }
  // Loaded when the last description the chain held is back at the host.
  clock_.catch_up(all_back);
}

}  // namespace rtsim::platform::ullner_pipeline
