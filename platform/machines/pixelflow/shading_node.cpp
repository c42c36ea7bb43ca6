#include "platform/machines/pixelflow/shading_node.hpp"

#include <algorithm>

#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::pixelflow {

namespace {
/// What the shading programs take from the frame: its materials' largest Phong exponent, its
/// textures' mip-map levels.
deferred::ProgramUniforms program_uniforms(const FrameSetup& frame) {
  deferred::ProgramUniforms u;
  for (const auto& m : frame.shading.materials) u.max_shine = std::max(u.max_shine, m.shine);
  int levels = 1;
  for (int size = frame.textures.label.size(); size > 1; size /= 2) ++levels;
  u.texture_levels = levels;
  return u;
}

const modules::CountParam kInputRegions(
    {.name = "input_regions",
     .default_value = "1",
     .min = "1",
     .max = "64",
     .unit = "regions",
     .description = "composited region-samples a shader can hold while it shades another",
     .source = "assumption: one, in the pixel processors' 128-byte communication registers, "
               "which hold a pixel's 34-byte record (seed 004 L15)"});
}  // namespace

void ShadingNode::declare_params(const modules::ParamDecls& d) {
  d.add(kInputRegions);
  ShadingCosts::declare_params(d);
  TableMemory::declare_params(d.sub("table"));
}

ShadingNode::ShadingNode(sc_core::sc_module_name name, MachineRun& run, const FrameSetup& frame,
                         const PassPlan& plan, int index, int count, const ProbeStages& stages)
    : modules::Processor(name, run.trace()),
      params_(run.registry(), this->name()),
      in("in", params_.get(kInputRegions)),
      out("out"),
      table("table", run, plan, frame.uses_textures ? frame.textures.bytes() : 0),
      frame_(frame),
      plan_(plan),
      index_(index),
      count_(count),
      costs_(params_, program_uniforms(frame)),
      regions_by_pass_(plan.passes.size(), 0),
      busy_by_pass_(plan.passes.size(), sc_core::SC_ZERO_TIME),
      probe_(run.probe()),
      stages_(stages),
      counters_(run.frame().counters()) {
  SC_THREAD(run);
}

void ShadingNode::await_maps(const Pass& p) {
  const auto ready = [&] {
    return p.kind == PassKind::Reflection ? table.shadows_begun() : table.maps_stored();
  };
  if (ready()) return;
  const sc_core::sc_time since = clock_.now();
  clock_.sync();
  while (!ready()) modules::sim_wait(table.ready_event());
  clock_.resync();
  waited_since(since, Wait::kData);
}

void ShadingNode::count_samples(const deferred::RegionWork& work,
                                const raster::RegionSampleGrid& at) {
  // The frame's counts in the terms every machine reports (stats.json `rays`, `hits`): a
  // camera sample is a primary visibility query, a shadow-map test a shadow ray's, a reflection-
  // map lookup a reflected ray's.
  const std::uint64_t samples =
      static_cast<std::uint64_t>(at.width) * static_cast<std::uint64_t>(at.height);
  counters_.rays[static_cast<std::size_t>(RayKind::Primary)] += samples;
  counters_.rays[static_cast<std::size_t>(RayKind::Shadow)] +=
      work.lookup(deferred::Lookup::Shadow);
  counters_.rays[static_cast<std::size_t>(RayKind::Reflected)] +=
      work.lookup(deferred::Lookup::Reflection);
  counters_.hits += work.lit_pixels;
}

void ShadingNode::run() {
  std::vector<Color> colours;
  for (std::size_t pi = 0; pi < plan_.passes.size(); ++pi) {
    const Pass& pass = plan_.passes[pi];
    if (pass.kind == PassKind::Shadow) continue;  // depth goes to the table memories
    // Its own table memory: the reflection pass shades without the reflection map.
    const deferred::ShadingTables tables =
        tables_of(frame_, table.maps(), pass.kind != PassKind::Camera);
    for (int k = index_; k < pass.region_samples(); k += count_) {
      const sc_core::sc_time since = clock_.now();
      modules::wait_for_item(in.fifo, clock_);
      sc_core::sc_time taken;
      const RasterRegion r = in.fifo.get(clock_.now(), taken);
      clock_.catch_up(taken);
      waited_since(since, Wait::kWork);
      probe_.add(r.journey, stages_.shader_in, modules::LatencyPart::kQueueing,
                 clock_.now() - r.arrived);
      // Its maps must be in table memory before it looks them up (L116, L128).
      const sc_core::sc_time ready = clock_.now();
      await_maps(pass);
      probe_.add(r.journey, stages_.shader, modules::LatencyPart::kQueueing, clock_.now() - ready);
      const deferred::RegionWork work =
          deferred::shade_region(*r.samples, pass.view, frame_.shading, tables, colours);
      const sc_core::sc_time shading = costs_.shading_part(work);
      const sc_core::sc_time t = shading + costs_.lookup_part(work);
      compute_for(t, "shade",
                  {{"pass", pi}, {"region", pass.region_of(k)}, {"sample", pass.sample_of(k)}});
      busy_by_pass_[pi] += t;
      ++regions_by_pass_[pi];
      ++regions_;
      for (const std::uint32_t n : work.pixels) pixels_shaded_ += n;
      for (const std::uint32_t n : work.lookups) lookups_ += n;
      if (t > worst_time_) {
        worst_time_ = t;
        worst_work_ = work;
      }
      if (shading > worst_shading_) {
        worst_shading_ = shading;
        worst_shading_work_ = work;
      }
      probe_.add(r.journey, stages_.shader, modules::LatencyPart::kService, t);
      ShadedRegion shaded{static_cast<int>(pi), k, r.samples->at, colour_bytes(colours)};
      const sc_core::sc_time done = clock_.now();
      wait_for_room(*out_queue_);
      probe_.add(r.journey, stages_.shader, modules::LatencyPart::kQueueing, clock_.now() - done);
      shaded.journey = r.journey;
      shaded.sent = clock_.now();
      if (pass.kind == PassKind::Camera) count_samples(work, r.samples->at);
      modules::send_message(out, shaded, clock_.now(), region_bits(kColourBytes));
    }
  }
  clock_.sync();
}

}  // namespace rtsim::platform::pixelflow
