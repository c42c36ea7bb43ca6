#include "platform/machines/sort_first/region_renderer.hpp"

#include "firmware/sortfirst/partial_image.hpp"
#include "modules/sim_time.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::sort_first {

namespace {
// A region renderer's rates. The seed gives none (its study counts primitives, L568); these are
// a 1995 geometry processor's (an i860 at 40 MHz, Pixel-Planes 5's, L554), each an assumption.
const modules::TimeParam kClassifyTime(
    {.name = "classify_time",
     .default_value = "2 us",
     .description = "transforming one primitive's three vertices to the screen and finding the "
                    "regions its bounding box covers",
     .source = "assumption: about 80 floating-point operations (3 vertex transforms, 3 "
               "divides, the box) at 40 MFLOPS"});
const modules::TimeParam kTriangleTime(
    {.name = "triangle_time",
     .default_value = "4 us",
     .description = "setting up one front-facing triangle for scan conversion (edge and "
                    "attribute equations)",
     .source = "assumption: a serial renderer's set-up, about twice a classification"});
const modules::TimeParam kSampleTime({.name = "sample_time",
                                      .default_value = "50 ns",
                                      .description = "scan-converting one covered sample with "
                                                     "its depth test and attributes",
                                      .source = "assumption: 20 Msamples/s"});
const modules::TimeParam kShadeTime({.name = "shade_time",
                                     .default_value = "200 ns",
                                     .description = "shading one covered pixel (Phong, every "
                                                    "light)",
                                     .source = "assumption: 5 Mpixels/s"});
}  // namespace

void MigrationFaults::pass(sortfirst::PrimitiveRecord& r) {
  for (auto& f : faults)
    if (f.word >= words_sent && f.word < words_sent + sortfirst::kRecordWords) {
      r.words[static_cast<std::size_t>(f.word - words_sent)] ^= f.xor_mask;
      f.applied = true;
    }
  words_sent += sortfirst::kRecordWords;
}

void RegionRenderer::declare_params(const modules::ParamDecls& d) {
  d.add(kClassifyTime);
  d.add(kTriangleTime);
  d.add(kSampleTime);
  d.add(kShadeTime);
}

RegionRenderer::RegionRenderer(sc_core::sc_module_name name, MachineRun& run, Interconnect& net,
                               const FrameData& data, sortfirst::Sort sort, int region, int host,
                               int frames, const std::vector<std::uint32_t>& share,
                               MigrationFaults& faults, const ProbeStages& stages)
    : InterconnectNode(name, run.trace(), net, region),
      // Every renderer reads its class's parameters ("renderer.triangle_time").
      params_(run.registry(), kClass),
      data_(data),
      region_(region),
      host_(host),
      frames_(frames),
      primitives_(static_cast<std::uint32_t>(data.mesh.triangles.size())),
      faults_(faults),
      probe_(run.probe()),
      frame_(run.frame()),
      stages_(stages),
      sort_(sort),
      store_(region, data.regions, data.shading.words.size(), sort),
      classify_time_(params_.get(kClassifyTime)),
      triangle_time_(params_.get(kTriangleTime)),
      sample_time_(params_.get(kSampleTime)),
      shade_time_(params_.get(kShadeTime)),
      sent_by_frame_(static_cast<std::size_t>(frames), 0),
      busy_by_frame_(static_cast<std::size_t>(frames), sc_core::SC_ZERO_TIME) {
  // The database initially partitioned among the processors (L499, L562).
  for (const std::uint32_t i : share) store_.load(sortfirst::pack(data.mesh.triangles[i], i));
  SC_THREAD(run);
}

template <class Done>
void RegionRenderer::receive_until(Done done) {
  while (!done()) {
    Message m = receive(Wait::kData);
    switch (m.kind) {
      case MessageKind::kView:
        views_[m.frame] = m.view;
        probe_.add(m.journey, stages_.net, modules::LatencyPart::kTransfer,
                   last_delivered_ - m.sent);
        probe_.add(m.journey, stages_.renderer_in, modules::LatencyPart::kQueueing,
                   last_taken_ - last_delivered_);
        journeys_[m.frame] = {m.journey, last_taken_};
        break;
      case MessageKind::kRecords: {
        auto& into = arrived_[m.frame];
        received_ += m.records.size();
        into.insert(into.end(), m.records.begin(), m.records.end());
        break;
      }
      case MessageKind::kExpected:
        expected_[m.frame] = m.count;
        break;
      case MessageKind::kTally:
      case MessageKind::kPixels:
      case MessageKind::kPartial:
        break;  // the host's
    }
  }
}

void RegionRenderer::busy(const sc_core::sc_time& t, std::string_view what, int frame) {
  compute_for(t, what, {{"frame", frame}});
  busy_by_frame_[static_cast<std::size_t>(frame)] += t;
}

void RegionRenderer::count_work(const sortfirst::RegionWork& w, std::uint64_t pixels) {
  triangles_ += w.triangles;
  samples_ += w.samples;
  shaded_ += w.shaded;
  // The frame's counts in the terms every machine reports (stats.json `rays`, `hits`), over
  // every frame of the path: a pixel is a primary visibility query, a shaded pixel's light
  // term the light's work as a shadow ray is a ray tracer's (no shadow is computed).
  auto& counters = frame_.counters();
  counters.rays[static_cast<std::size_t>(RayKind::Primary)] += pixels;
  counters.rays[static_cast<std::size_t>(RayKind::Shadow)] +=
      w.shaded * data_.shading.setup.lights.size();
  counters.hits += w.shaded;
}

void RegionRenderer::redistribute(int f, const raster::ViewTransform& view,
                                  std::vector<sortfirst::Migration>& sends) {
  const auto fi = static_cast<std::size_t>(f);
  std::map<int, Message> out;
  for (auto& s : sends) {
    Message& m = out[s.to];
    m.kind = MessageKind::kRecords;
    m.frame = f;
    faults_.pass(s.record);
    m.records.push_back(s.record);
  }
  Message tally;
  tally.kind = MessageKind::kTally;
  tally.frame = f;
  for (auto& [to, m] : out) {
    tally.tally.emplace_back(to, static_cast<std::uint32_t>(m.records.size()));
    sent_by_frame_[fi] += m.records.size();
    sent_ += m.records.size();
    send(to, std::move(m));
  }
  send(host_, std::move(tally));
  // What comes to it: as many records as the host says.
  receive_until([&] {
    const auto e = expected_.find(f);
    return e != expected_.end() && arrived_[f].size() >= e->second;
  });
  std::uint64_t kept = 0;
  const auto& arrived = arrived_[f];
  for (const auto& r : arrived) kept += store_.receive(r, view, primitives_) ? 1 : 0;
  refused_ += arrived.size() - kept;
  // A sort-first arrival is transformed again by its new holder; sort-middle sends primitives
  // already transformed (L509-L511).
  if (sort_ == sortfirst::Sort::First) {
    classified_ += arrived.size();
    busy(modules::times(classify_time_, arrived.size()), "classify arrivals", f);
  }
}

void RegionRenderer::run() {
  for (int f = 0; f < frames_; ++f) {
    const auto fi = static_cast<std::size_t>(f);
    receive_until([&] { return views_.count(f) > 0; });
    const raster::ViewTransform view = views_[f];
    // Classification (L503) and, but for sort-last, redistribution.
    sortfirst::ClassifyResult res = store_.classify_all(view);
    classified_ += res.classified;
    dropped_ += res.dropped_copies;
    busy(modules::times(classify_time_, res.classified), "classify", f);
    if (sort_ != sortfirst::Sort::Last) redistribute(f, view, res.sends);
    std::vector<Message> results;
    if (sort_ == sortfirst::Sort::Last) {
      // Its share over the whole screen, each tile of the partial image sent to be composited.
      sortfirst::PartialImage partial = sortfirst::render_partial(
          store_.to_render(), view, data_.regions.width, data_.regions.height, data_.shading.words);
      count_work(partial.work, partial.work.shaded);
      busy(render_time(partial.work), "render", f);
      for (auto& tile : partial.tiles) {
        Message m;
        m.kind = MessageKind::kPartial;
        m.frame = f;
        m.partial = std::move(tile);
        results.push_back(std::move(m));
      }
    } else {
      // Its region, from what it holds (L505).
      auto pixels = std::make_shared<sortfirst::RegionPixels>(sortfirst::render_region(
          store_.to_render(), view, data_.regions, region_, data_.shading));
      count_work(pixels->work, pixels->pixels.size());
      busy(render_time(pixels->work), "render", f);
      Message m;
      m.kind = MessageKind::kPixels;
      m.frame = f;
      m.pixels = std::move(pixels);
      results.push_back(std::move(m));
    }
    // The region's frame at this renderer, computing and waiting for its records; its journey
    // goes on with the last message it sends.
    const auto [journey, taken] = journeys_[f];
    results.back().journey = journey;
    probe_.add(journey, stages_.renderer, modules::LatencyPart::kService, busy_by_frame_[fi]);
    probe_.add(journey, stages_.renderer, modules::LatencyPart::kQueueing,
               clock_.now() - taken - busy_by_frame_[fi]);
    journeys_.erase(f);
    for (auto& m : results) send(host_, std::move(m));
    views_.erase(f);
    expected_.erase(f);
    arrived_.erase(f);
  }
  clock_.sync();
}

sc_core::sc_time RegionRenderer::render_time(const sortfirst::RegionWork& w) const {
  return modules::times(triangle_time_, w.triangles) + modules::times(sample_time_, w.samples) +
         modules::times(shade_time_, w.shaded);
}

}  // namespace rtsim::platform::sort_first
