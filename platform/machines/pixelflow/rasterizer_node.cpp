#include "platform/machines/pixelflow/rasterizer_node.hpp"

#include "modules/sim_time.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::pixelflow {

namespace {
const modules::TimeParam kTriangleTime(
    {.name = "triangle_time",
     .default_value = "850 ns",
     .description = "setting up and scan-converting one front-facing triangle for one "
                    "region-sample with all its appearance parameters",
     .source = "seed 004 L132"});
const modules::TimeParam kDepthTriangleTime(
    {.name = "depth_triangle_time",
     .default_value = "850 ns",
     .description = "the same for depth only (a shadow map's pass)",
     .source = "assumption: the seed gives no depth-only rate (L118: 'a simple computation'); "
               "the full rate is its upper bound, and a map pass's time is set by its table "
               "writes (L126) unless this is far larger"});
const modules::CountParam kBufferedRegions(
    {.name = "buffered_regions",
     .default_value = "2",
     .min = "1",
     .max = "64",
     .unit = "regions",
     .description = "finished region-samples a rasterizer holds until the composition network "
                    "takes them",
     .source = "assumption: seed 004 L128 says rasterization waits for free buffer space but "
               "not how much there is; two lets a rasterizer work on one while the network "
               "takes the other"});
}  // namespace

void RasterizerNode::declare_params(const modules::ParamDecls& d) {
  d.add(kTriangleTime);
  d.add(kDepthTriangleTime);
  d.add(kBufferedRegions);
}

std::size_t RasterizerNode::buffered_regions(const modules::ModuleParams& p) {
  return p.get(kBufferedRegions);
}

RasterizerNode::RasterizerNode(sc_core::sc_module_name name, MachineRun& run, const PassPlan& plan,
                               int index, const modules::TimedFifo<RasterRegion>& out_queue)
    : modules::Processor(name, run.trace()),
      out("out"),
      params_(run.registry(), this->name()),
      plan_(plan),
      index_(index),
      out_queue_(out_queue),
      triangle_time_(params_.get(kTriangleTime)),
      depth_triangle_time_(params_.get(kDepthTriangleTime)),
      busy_by_pass_(plan.passes.size(), sc_core::SC_ZERO_TIME),
      triangles_by_pass_(plan.passes.size(), 0),
      began_pass_(plan.passes.size(), sc_core::SC_ZERO_TIME) {
  SC_THREAD(run);
}

void RasterizerNode::run() {
  for (std::size_t pi = 0; pi < plan_.passes.size(); ++pi) {
    const Pass& pass = plan_.passes[pi];
    for (int k = 0; k < pass.region_samples(); ++k) {
      const int region = pass.region_of(k);
      const auto& share =
          pass.shares[static_cast<std::size_t>(region)][static_cast<std::size_t>(index_)];
      const raster::RegionSampleGrid g =
          raster::RegionSampleGrid::of(pass.grid, region, pass.sample_of(k));
      RasterRegion msg{static_cast<int>(pi), k, nullptr, nullptr};
      msg.begun = clock_.now();
      if (k == 0) began_pass_[pi] = msg.begun;
      std::uint64_t written = 0;
      if (pass.depth_only()) {
        msg.depths = std::make_shared<raster::RegionDepths>(g);
        for (const std::uint32_t i : share)
          written += raster::scan_depth(pass.setup.triangles[i], pass.view, *msg.depths).written;
      } else {
        msg.samples = std::make_shared<raster::RegionSamples>(g);
        for (const std::uint32_t i : share)
          written += raster::scan_convert(pass.setup.triangles[i], pass.view, *msg.samples).written;
      }
      const sc_core::sc_time t =
          modules::times(pass.depth_only() ? depth_triangle_time_ : triangle_time_, share.size());
      compute_for(t, "rasterize",
                  {{"pass", pi},
                   {"region", region},
                   {"sample", pass.sample_of(k)},
                   {"triangles", share.size()}});
      msg.finished = clock_.now();
      busy_by_pass_[pi] += t;
      triangles_by_pass_[pi] += share.size();
      triangles_ += share.size();
      samples_written_ += written;
      ++regions_;
      wait_for_room(out_queue_);
      modules::send_message(out, msg, clock_.now(), region_bits(pass.bytes_per_pixel()));
    }
  }
  clock_.sync();
}

}  // namespace rtsim::platform::pixelflow
