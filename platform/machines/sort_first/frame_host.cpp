#include "platform/machines/sort_first/frame_host.hpp"

#include "modules/sim_time.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::sort_first {

namespace {
const modules::TimeParam kCompositeTime(
    {.name = "composite_time",
     .default_value = "10 ns",
     .description = "sort-last: depth-compositing one sample of a partial image into the frame",
     .source = "assumption: a composition network's compare at 100 Msamples/s (the seed names "
               "specialized composition networks, L517, without a rate)"});
}  // namespace

void FrameHost::declare_params(const modules::ParamDecls& d) { d.add(kCompositeTime); }

FrameHost::FrameHost(sc_core::sc_module_name name, MachineRun& run, Interconnect& net,
                     const FrameData& data, sortfirst::Sort sort, int node, int regions,
                     std::vector<raster::ViewTransform> views, const ProbeStages& stages)
    : InterconnectNode(name, run.trace(), net, node),
      frame_(run.frame()),
      data_(data),
      sort_(sort),
      probe_(run.probe()),
      stages_(stages),
      regions_(regions),
      views_(std::move(views)),
      composite_time_(modules::ModuleParams(run.registry(), kName).get(kCompositeTime)) {
  SC_THREAD(run);
}

void FrameHost::take_tally(const Message& m, int f) {
  for (const auto& [to, n] : m.tally) expected_[static_cast<std::size_t>(to)] += n;
  if (++tallies_ < regions_) return;
  for (int k = 0; k < regions_; ++k) {
    Message e;
    e.kind = MessageKind::kExpected;
    e.frame = f;
    e.count = expected_[static_cast<std::size_t>(k)];
    send(k, std::move(e));
  }
}

bool FrameHost::take_result(Message m, int f, bool last_frame) {
  if (m.journey != modules::LatencyProbe::kNoJourney) {
    probe_.add(m.journey, stages_.net, modules::LatencyPart::kTransfer, last_delivered_ - m.sent);
    probe_.add(m.journey, stages_.host_in, modules::LatencyPart::kQueueing,
               last_taken_ - last_delivered_);
    probe_.end(m.journey, last_taken_);
  }
  if (m.kind == MessageKind::kPixels && m.pixels) {
    pixels_ += m.pixels->pixels.size();
    if (last_frame) paint_region(frame_, *m.pixels);
    return true;
  }
  if (m.kind != MessageKind::kPartial || !m.partial) return false;
  // Sort-last: composite the tile; shade it (the last frame) once every renderer's is in.
  const raster::RegionSampleGrid& g = m.partial->at;
  const auto t = static_cast<std::size_t>(g.region);
  const std::uint64_t samples =
      static_cast<std::uint64_t>(g.width) * static_cast<std::uint64_t>(g.height);
  compute_for(modules::times(composite_time_, samples), "composite", {{"frame", f}});
  composited_ += samples;
  if (!composite_[t])
    composite_[t].emplace(*m.partial);
  else
    raster::z_composite(*composite_[t], *m.partial);
  if (++tiles_in_[t] == regions_) {
    sortfirst::RegionPixels tile;
    tile.x0 = g.x0;
    tile.y0 = g.y0;
    tile.width = g.width;
    tile.height = g.height;
    tile.pixels.assign(samples, sortfirst::PixelBytes{});
    if (last_frame) {
      sortfirst::shade_tile(*composite_[t], views_[static_cast<std::size_t>(f)], data_.shading,
                            tile);
      paint_region(frame_, tile);
    }
    pixels_ += samples;
    composite_[t].reset();
  }
  return ++renderer_tiles_[static_cast<std::size_t>(m.from)] == static_cast<int>(composite_.size());
}

void FrameHost::run() {
  const int frames = static_cast<int>(views_.size());
  const int tiles = raster::RegionGrid{data_.regions.width, data_.regions.height}.count();
  for (int f = 0; f < frames; ++f) {
    began_.push_back(clock_.now());
    expected_.assign(static_cast<std::size_t>(regions_), 0);
    tallies_ = 0;
    composite_.assign(sort_ == sortfirst::Sort::Last ? static_cast<std::size_t>(tiles) : 0,
                      std::nullopt);
    tiles_in_.assign(composite_.size(), 0);
    renderer_tiles_.assign(static_cast<std::size_t>(regions_), 0);
    for (int k = 0; k < regions_; ++k) {
      Message v;
      v.kind = MessageKind::kView;
      v.frame = f;
      v.view = views_[static_cast<std::size_t>(f)];
      // A region's frame's journey: from its view handed over to its result taken.
      v.journey = probe_.begin(clock_.now());
      send(k, std::move(v));
    }
    int done = 0;
    while (done < regions_) {
      Message m = receive(Wait::kData);
      if (m.frame != f) continue;  // nothing of another frame is addressed to the host
      if (m.kind == MessageKind::kTally)
        take_tally(m, f);
      else if (take_result(std::move(m), f, f == frames - 1))
        ++done;
    }
    ended_.push_back(clock_.now());
  }
  clock_.sync();
}

}  // namespace rtsim::platform::sort_first
