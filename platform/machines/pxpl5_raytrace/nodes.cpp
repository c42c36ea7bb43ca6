#include "platform/machines/pxpl5_raytrace/nodes.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

#include "common/input_error.hpp"
#include "firmware/tasks/lattice_ray_task.hpp"
#include "firmware/tasks/region_sampling.hpp"
#include "modules/module_params.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::pxpl5 {

namespace {

// The nodes' costs, each named once (the seed gives none: note 004 A).
const modules::TimeParam kAssignTime(
    {.name = "assign_time",
     .default_value = "20 us",
     .max = "1 s",
     .description = "Master GP time to take a request and hand out a region",
     .source = "assumption: the seed gives no master GP costs (Fig. 5, L347, measures its limit "
               "without numbers); 800 i860 cycles"});
const modules::ChoiceParam kFrameBarrier(
    {.name = "next_frame",
     .default_value = "after_casting",
     .allowed = {"after_casting", "after_handing_out"},
     .description =
         "When the master GP starts handing out a started frame's regions: once every region of "
         "the frame before has been cast (after_casting: the casters meet at the frame's end, "
         "and the compositors, renderers and frame buffer overlap the next frame's casting), or "
         "once they have all been handed out (after_handing_out: idle casters take the next "
         "frame's regions while the last ones of this frame are cast)",
     .source = "seed 004 L296 (the master GP \"is responsible for system synchronization\"); "
               "assumption: after_casting, under which L360's 10-20% gain of the cost order, "
               "which shortens the frame's tail, is seen"});
const modules::ChoiceParam kOrder(
    {.name = "order",
     .default_value = "cost",
     .allowed = {"screen", "cost"},
     .description = "Order the regions are handed out in: screen order, or descending cost in "
                    "the previous frame (0th-order prediction)",
     .source = "seed 004 L360"});
const modules::TimeParam kSampleTime(
    {.name = "sample_time",
     .default_value = "500 ns",
     .max = "1 s",
     .description = "Compositor GP time per sample received (store it in its band)",
     .source = "assumption: 20 i860 cycles a sample"});
const modules::TimeParam kTileTime(
    {.name = "tile_time",
     .default_value = "1 ms",
     .max = "1 s",
     .description = "SIMD renderer time to resample its 128 x 128 tile (all pixels at once, "
                    "whatever their content)",
     .source = "assumption: the seed gives none (Fig. 6, L350, without numbers)"});
const modules::IntParam kDisplayFrame(
    {.name = "frame",
     .default_value = "-1",
     .min = "-1",
     .max = "99999",
     .unit = "frame",
     .description = "The frame whose displayed image is written (image.png, image.exr), counted "
                    "from 0; -1: the last. An earlier frame shows what the user saw then (a "
                    "coarse or partly updated image)",
     .source = "simulator setting, not of the machine",
     .affects_image = true});
const modules::TimeParam kPixelTime({.name = "pixel_time",
                                     .default_value = "10 ns",
                                     .max = "1 s",
                                     .description = "Frame buffer time to write one display pixel",
                                     .source = "assumption"});

const modules::CountParam kFramesInFlight(
    {.name = "frames_in_flight",
     .default_value = "2",
     .min = "1",
     .max = "64",
     .unit = "frames",
     .description =
         "Frames the host lets into the pipeline before the oldest of them is displayed: 1 "
         "serialises them (the next starts when the frame buffer has the last); 2 lets the "
         "master and the casters work on frame k+1 while the compositors, renderers and frame "
         "buffer finish frame k. A compositor holds a later frame's samples until its bands "
         "have sent the earlier one, a renderer a tile a frame in flight",
     .source = "seed 004 L270, L420 (\"a pipelined renderer\"); assumption: two, the front "
               "end (master, casters) and the back end (compositors, splatters, frame buffer) "
               "each on its own frame (Fig. 1)"});

/// Where each is declared and read: its node's class (the master's order is the assignment's).
constexpr const char* kPipeline = "pipeline";
constexpr const char* kMaster = "master";
constexpr const char* kAssign = "assign";
constexpr const char* kCompositor = "compositor";
constexpr const char* kRenderer = "renderer";
constexpr const char* kFrameBuffer = "frame_buffer";
constexpr const char* kDisplay = "display";

}  // namespace

// --- Host ---------------------------------------------------------------------------------

void Host::declare_params(params::ParamRegistry& r) {
  modules::ParamDecls(r, kPipeline, false).add(kFramesInFlight);
}

Host::Host(sc_core::sc_module_name name, MachineRun& run, modules::RingChannel<Message>& ring,
           const Setup& setup)
    : RingNode(name, run.trace(), ring, setup.layout.host(), setup.sizes),
      run_(run),
      setup_(setup),
      in_flight_(
          static_cast<int>(modules::ModuleParams(run.registry(), kPipeline).get(kFramesInFlight))) {
  SC_THREAD(run);
}

void Host::start(int f) {
  started_.push_back(clock_.now());
  Message start;
  start.kind = Kind::kStartFrame;
  start.frame = f;
  send(setup_.layout.master(), std::move(start));
}

void Host::run() {
  // Up to frames_in_flight frames in the pipeline (L270); each display lets the next one in.
  int next = 0;
  while (next < setup_.frames && next < in_flight_) start(next++);
  while (done_.size() < static_cast<std::size_t>(setup_.frames)) {
    // A passive sink: it waits for work, not for data it asked for.
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kFrameDone) continue;
    done_.push_back(clock_.now());  // the frame buffer displays frames in order
    if (run_.options().progress)
      run_.options().progress(static_cast<int>(done_.size()), setup_.frames);
    if (next < setup_.frames) start(next++);
  }
}

// --- Master GP ----------------------------------------------------------------------------

void MasterGp::declare_params(params::ParamRegistry& r) {
  const modules::ParamDecls master(r, kMaster, false);
  master.add(kAssignTime);
  master.add(kFrameBarrier);
  modules::ParamDecls(r, kAssign, false).add(kOrder);
}

MasterGp::MasterGp(sc_core::sc_module_name name, MachineRun& run,
                   modules::RingChannel<Message>& ring, const Setup& setup)
    : RingNode(name, run.trace(), ring, setup.layout.master(), setup.sizes),
      setup_(setup),
      assign_time_(modules::ModuleParams(run.registry(), kMaster).get(kAssignTime)),
      after_casting_(modules::ModuleParams(run.registry(), kMaster).get(kFrameBarrier) ==
                     "after_casting"),
      cost_order_(modules::ModuleParams(run.registry(), kAssign).get(kOrder) == "cost") {
  set_timing(setup.gp_timing);
  SC_THREAD(run);
}

void MasterGp::assign(int caster) {
  if (!setup_.bypass.master) compute_for(assign_time_, "assign", {{"caster", caster}});
  Message a;
  a.kind = Kind::kAssign;
  a.frame = frame_;
  a.region = regions_[next_++];
  ++assignments_;
  send(caster, std::move(a));
}

void MasterGp::begin_frame(int f) {
  frame_ = f;
  regions_ = setup_.layout.regions();
  if (cost_.size() < regions_.size()) cost_.resize(regions_.size(), 0.0);
  // A sampled frame: the detailed regions only (the others were cast functionally).
  if (setup_.sample)
    std::erase_if(regions_, [&](const Region& g) { return !setup_.sample->detailed_unit(g.id); });
  // A resting view that is fully refined casts nothing: no region is handed out.
  if (setup_.schedule.plan(f).cast_level < 0) regions_.clear();
  // The compositors learn the frame has begun (L296: the master synchronises the system): one
  // whose bands get no sample this frame still sends them on.
  for (int k = 0; k < setup_.layout.compositors; ++k) {
    Message begin;
    begin.kind = Kind::kFrameBegin;
    begin.frame = f;
    send(setup_.layout.compositor(k), std::move(begin));
  }
  // 0th-order cost prediction (L360): the costliest first, by what each cost when last cast
  // (with frames in flight, a region of the previous frame still being cast counts its cost
  // before that).
  if (cost_order_ && frame_ > 0)
    std::stable_sort(regions_.begin(), regions_.end(), [&](const Region& a, const Region& b) {
      return cost_[static_cast<std::size_t>(a.id)] > cost_[static_cast<std::size_t>(b.id)];
    });
  next_ = 0;
  cast_ = 0;
  std::vector<int> waiting;
  waiting.swap(waiting_);
  for (int c : waiting) {
    if (next_ < regions_.size())
      assign(c);
    else
      waiting_.push_back(c);
  }
}

void MasterGp::run() {
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind == Kind::kStartFrame) {
      // A frame started while the previous one still has regions to hand out waits its turn.
      starts_.push_back(m.frame);
    } else if (m.kind == Kind::kRequest) {
      if (m.last_region >= 0 && static_cast<std::size_t>(m.last_region) < cost_.size())
        cost_[static_cast<std::size_t>(m.last_region)] = m.last_cost_s;
      if (m.last_region >= 0 && m.frame == frame_) ++cast_;
      // First come, first served (L352); a request after the frame's last region waits for the
      // next frame.
      if (frame_ >= 0 && next_ < regions_.size())
        assign(m.from);
      else
        waiting_.push_back(m.from);
    }
    // Once a frame's regions are all cast (or all given out: master.next_frame), the next
    // started frame's are handed out.
    while ((frame_ < 0 || next_ >= regions_.size()) &&
           (frame_ < 0 || !after_casting_ || cast_ >= regions_.size()) && !starts_.empty()) {
      const int f = starts_.front();
      starts_.pop_front();
      begin_frame(f);
    }
  }
}

// --- Ray caster ---------------------------------------------------------------------------

RayCaster::RayCaster(sc_core::sc_module_name name, MachineRun& run,
                     modules::RingChannel<Message>& ring, const Setup& setup, int number,
                     SamplesFault& fault)
    : RingNode(name, run.trace(), ring, setup.layout.caster(number), setup.sizes),
      run_(run),
      setup_(setup),
      fault_(fault),
      shade_(run.scene(), run.twin().settings.shade) {
  set_timing(setup.gp_timing);
  SC_THREAD(run);
}

void RayCaster::run() {
  Message request;
  request.kind = Kind::kRequest;
  send(setup_.layout.master(), request);
  const Layout& lay = setup_.layout;
  const tasks::SampleLattice lattice = lay.lattice();
  functional::FrameState& frame = run_.frame();
  const int spp = frame.spp();
  TraceCounters& counters = frame.counters();
  tasks::LatticeRayTask task(*run_.twin().tracer, shade_, counters);
  std::vector<std::vector<Sample>> by_compositor(static_cast<std::size_t>(lay.compositors));
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kAssign) continue;
    const sc_core::sc_time began = clock_.now();
    const Region& g = m.region;
    // The displayed frame's primary hits (display.frame: the image's AOVs and coverage).
    const bool last_frame = m.frame == setup_.display_frame;
    const shading::PinholeCamera& camera = setup_.cameras[static_cast<std::size_t>(m.frame)];
    const Cost before = counters.cost;
    const auto cast = [&](int i, int j) {
      if (setup_.bypass.casters) {
        Sample none;  // by-pass code: the message, no ray (L333)
        none.index = lattice.index(i, j);
        return none;
      }
      const std::int64_t pixel = last_frame ? lattice.pixel(i, j) : -1;
      if (pixel >= 0) ++cast_last_frame_;
      return task.cast(camera, lattice, i, j, spp, [&](bool found, const Hit& hit) {
        if (pixel < 0) return;
        if (found) ++covered_last_frame_;
        frame.record_primary(static_cast<std::uint32_t>(pixel), found, hit);
      });
    };
    const auto update = [&](int i, int j) { return setup_.schedule.casts(i, j, m.frame); };
    const auto out = [&](const Sample& s) {
      by_compositor[static_cast<std::size_t>(lay.compositor_of_lattice_row(lattice.j_of(s.index)))]
          .push_back(s);
      ++samples_;
    };
    const std::size_t rays =
        tasks::sample_region(lattice, lay.rule, g.lattice, spp, cast, update, out);
    rays_ += rays;
    Cost spent = counters.cost;
    spent -= before;
    if (!setup_.bypass.casters)
      compute(spent, "region", {{"region", g.id}, {"pixels", g.w * g.h}, {"rays", rays}});
    ++regions_;
    // The samples go to the compositors owning their rows (L310).
    for (int k = 0; k < lay.compositors; ++k) {
      auto& samples = by_compositor[static_cast<std::size_t>(k)];
      if (samples.empty()) continue;
      Message out_msg = take_samples(Kind::kSamples, m.frame, samples);
      out_msg.began = began;
      out_msg.sent = clock_.now();
      fault_.on_send(out_msg, spp);
      send(lay.compositor(k), std::move(out_msg));
    }
    if (setup_.sample) setup_.sample->unit_done(g.id, began.value(), clock_.now().value());
    Message next;
    next.kind = Kind::kRequest;
    next.frame = m.frame;
    next.last_region = g.id;
    next.last_cost_s = (clock_.now() - began).to_seconds();
    send(lay.master(), std::move(next));
  }
}

// --- Compositor ---------------------------------------------------------------------------

void Compositor::declare_params(params::ParamRegistry& r) {
  modules::ParamDecls(r, kCompositor, false).add(kSampleTime);
}

Compositor::Compositor(sc_core::sc_module_name name, MachineRun& run,
                       modules::RingChannel<Message>& ring, const Setup& setup, int number)
    : RingNode(name, run.trace(), ring, setup.layout.compositor(number), setup.sizes),
      run_(run),
      setup_(setup),
      number_(number),
      sample_time_(modules::ModuleParams(run.registry(), kCompositor).get(kSampleTime)) {
  set_timing(setup.gp_timing);
  const Layout& lay = setup.layout;
  const std::vector<Region> regions = lay.regions();
  // By frame: the samples the casters send it (the schedule's casts in its rows), counted once
  // for each level and phase a frame can cast.
  std::map<std::pair<int, int>, long> by_plan;
  for (int f = 0; f < setup.frames; ++f) {
    const tasks::FramePlan& plan = setup.schedule.plan(f);
    const auto [it, added] = by_plan.try_emplace({plan.cast_level, plan.phase}, 0);
    if (added)
      for (const Region& g : regions)
        it->second += lay.positions_sent(g, number, setup.schedule, f);
    expected_.push_back(it->second);
  }
  SC_THREAD(run);
}

void Compositor::probe_samples(const Message& m) {
  modules::LatencyProbe* probe = &run_.probe();
  if (!probe->enabled()) return;
  using modules::LatencyPart;
  const auto& st = setup_.stages;
  // Every sample of the message went the same way: the region's cast (its samples are done
  // together), the ring (waiting for the token and carried), the inbox, the compositing.
  const Layout& lay = setup_.layout;
  const tasks::SampleLattice lattice = lay.lattice();
  auto& held = held_journeys_[m.frame];
  for (const Sample& sample : m.samples) {
    const auto j = probe->begin(m.began);
    probe->add(j, st.caster, LatencyPart::kService, m.sent - m.began);
    probe->add(j, st.ring, LatencyPart::kTransfer, last_delivered_ - m.sent);
    probe->add(j, st.inbox, LatencyPart::kQueueing, last_taken_ - last_delivered_);
    probe->add(j, st.compositor, LatencyPart::kService, clock_.now() - last_taken_);
    // The renderer of its own display pixel (the one under it, or the image's last).
    const int x = std::min(lattice.i_of(sample.index) * lay.rule.finest, lay.width - 1);
    const int y = std::min(lattice.j_of(sample.index) * lay.rule.finest, lay.height - 1);
    held.push_back({j, lay.renderer_of(x, y), clock_.now()});
  }
}

void Compositor::probe_bands_sent(int frame) {
  const auto h = held_journeys_.find(frame);
  if (h == held_journeys_.end()) return;
  modules::LatencyProbe& probe = run_.probe();
  for (const Held& s : h->second) {
    // Held until the bands had the frame (the frame's other samples, and the frame before).
    probe.add(s.journey, setup_.stages.compositor, modules::LatencyPart::kQueueing,
              clock_.now() - s.composited);
    setup_.journeys->to_renderer[{frame, s.renderer}].push_back({s.journey, number_, clock_.now()});
  }
  held_journeys_.erase(h);
}

long Compositor::expected(int frame) const { return expected_[static_cast<std::size_t>(frame)]; }

void Compositor::run() {
  const Layout& lay = setup_.layout;
  const tasks::SampleLattice lattice = lay.lattice();
  // The persistent sample array of its bands (L379): the rows it owns, in order.
  std::vector<int> local_row(static_cast<std::size_t>(lattice.ny()), -1);
  std::vector<int> rows;
  for (int j = 0; j < lattice.ny(); ++j)
    if (lay.compositor_of_lattice_row(j) == number_) {
      local_row[static_cast<std::size_t>(j)] = static_cast<int>(rows.size());
      rows.push_back(j);
    }
  const auto nx = static_cast<std::size_t>(lattice.nx());
  std::vector<Sample> kept(rows.size() * nx);
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t i = 0; i < nx; ++i)
      kept[r * nx + i].index = lattice.index(static_cast<int>(i), rows[r]);
  std::vector<int> written(kept.size(), -1);  // the frame each position was last written in
  // By refinement level: the renderers reading each lattice column and row of its grid.
  const tasks::RefinementSchedule& schedule = setup_.schedule;
  std::vector<std::vector<std::vector<int>>> tile_cols, tile_rows;
  for (int l = 0; l < schedule.levels(); ++l) {
    tile_cols.push_back(lay.tiles_reading(false, schedule.step(l)));
    tile_rows.push_back(lay.tiles_reading(true, schedule.step(l)));
  }
  std::vector<std::vector<Sample>> by_renderer(static_cast<std::size_t>(lay.renderers()));
  const auto keep = [&](const Sample& s, int frame) {
    const int j = lattice.j_of(s.index), i = lattice.i_of(s.index);
    const std::size_t k = static_cast<std::size_t>(local_row[static_cast<std::size_t>(j)]) * nx +
                          static_cast<std::size_t>(i);
    tasks::keep_copy(kept[k], written[k], s, frame);
  };
  // By frame: samples received. Frames are composited into the persistent array in order: a
  // later frame's samples (frames in flight) wait in `held` until this frame's bands are sent.
  std::map<int, long> have;
  std::map<int, std::vector<Sample>> held;
  std::set<int> begun;  // frames the master has begun handing out
  int current = 0;
  // A sampled frame: the regions not simulated in detail are here from the start.
  if (!setup_.functional_samples.empty())
    for (const Sample& s : setup_.functional_samples[static_cast<std::size_t>(number_)]) {
      keep(s, 0);
      ++have[0];
    }
  for (;;) {
    Message m = receive(Wait::kWork);
    if (m.kind == Kind::kFrameBegin) {
      begun.insert(m.frame);
    } else if (m.kind == Kind::kSamples) {
      if (!setup_.bypass.back_end)
        compute_for(modules::times(sample_time_, m.samples.size()), "composite",
                    {{"samples", m.samples.size()}});
      probe_samples(m);
      samples_ += m.samples.size();
      have[m.frame] += static_cast<long>(m.samples.size());
      if (m.frame == current) {
        for (const Sample& s : m.samples) keep(s, m.frame);
      } else {
        auto& later = held[m.frame];
        later.insert(later.end(), m.samples.begin(), m.samples.end());
      }
    } else {
      continue;
    }
    while (current < setup_.frames && begun.contains(current) &&
           have[current] >= expected(current)) {
      // Its bands have the frame: each renderer gets the positions its tile reads on the grid
      // of the level the frame is displayed at (a variable-size array, L312).
      const int level = schedule.plan(current).display_level;
      const auto step = static_cast<std::size_t>(schedule.step(level));
      const auto& cols = tile_cols[static_cast<std::size_t>(level)];
      const auto& lines = tile_rows[static_cast<std::size_t>(level)];
      for (std::size_t r = 0; r < rows.size(); ++r) {
        if (static_cast<std::size_t>(rows[r]) % step != 0) continue;
        for (std::size_t i = 0; i < nx; i += step) {
          const Sample& s = kept[r * nx + i];
          for (int ty : lines[static_cast<std::size_t>(rows[r])])
            for (int tx : cols[i])
              by_renderer[static_cast<std::size_t>(ty * lay.tiles_x() + tx)].push_back(s);
        }
      }
      for (int k = 0; k < lay.renderers(); ++k) {
        auto& part = by_renderer[static_cast<std::size_t>(k)];
        if (!part.empty()) send(lay.renderer(k), take_samples(Kind::kBand, current, part));
      }
      if (setup_.journeys) probe_bands_sent(current);
      have.erase(current);
      begun.erase(current);
      ++current;
      if (const auto h = held.find(current); h != held.end()) {
        for (const Sample& s : h->second) keep(s, current);
        held.erase(h);
      }
    }
  }
}

// --- Renderer -----------------------------------------------------------------------------

void Renderer::declare_params(params::ParamRegistry& r) {
  modules::ParamDecls(r, kRenderer, false).add(kTileTime);
}

Renderer::Renderer(sc_core::sc_module_name name, MachineRun& run,
                   modules::RingChannel<Message>& ring, const Setup& setup, int number)
    : RingNode(name, run.trace(), ring, setup.layout.renderer(number), setup.sizes),
      run_(run),
      setup_(setup),
      number_(number),
      tile_time_(modules::ModuleParams(run.registry(), kRenderer).get(kTileTime)) {
  SC_THREAD(run);
}

void Renderer::probe_tile(int frame, const sc_core::sc_time& began,
                          const std::map<int, sc_core::sc_time>& delivered) {
  using modules::LatencyPart;
  modules::LatencyProbe& probe = run_.probe();
  const auto& st = setup_.stages;
  SampleJourneys& book = *setup_.journeys;
  const auto in = book.to_renderer.find({frame, number_});
  auto& out = book.to_frame_buffer[{frame, number_}];
  out.sent = clock_.now();  // its pixels go to the frame buffer now
  if (in == book.to_renderer.end()) return;
  for (const SampleJourneys::InBand& b : in->second) {
    const auto d = delivered.find(b.compositor);
    const sc_core::sc_time arrived = d == delivered.end() ? b.sent : d->second;
    probe.add(b.journey, st.ring, LatencyPart::kTransfer, arrived - b.sent);
    // Waiting for the frame's other bands (and the tile before), then resampling the tile.
    probe.add(b.journey, st.renderer, LatencyPart::kQueueing, began - arrived);
    probe.add(b.journey, st.renderer, LatencyPart::kService, clock_.now() - began);
    out.journeys.push_back(b.journey);
  }
  book.to_renderer.erase(in);
}

void Renderer::run() {
  const Layout& lay = setup_.layout;
  const tasks::SampleLattice lattice = lay.lattice();
  const tasks::RefinementSchedule& schedule = setup_.schedule;
  // By refinement level: the lattice range its tile reads on the level's grid, and how many
  // grid positions that is.
  struct Reads {
    tasks::LatticeRange range;
    int step = 1;
    long positions = 0;
  };
  std::vector<Reads> reads;
  for (int l = 0; l < schedule.levels(); ++l) {
    const int step = schedule.step(l);
    const tasks::LatticeRange r = lay.lattice_of_renderer(number_, step);
    reads.push_back(
        {r, step,
         static_cast<long>((r.i1 - 1 - r.i0) / step + 1) * ((r.j1 - 1 - r.j0) / step + 1)});
  }
  const int tx = number_ % lay.tiles_x(), ty = number_ / lay.tiles_x();
  const int x0 = tx * lay.tile, y0 = ty * lay.tile;
  const int x1 = std::min(x0 + lay.tile, lay.width), y1 = std::min(y0 + lay.tile, lay.height);
  // By frame in flight: its tile and the positions received; tiles are resampled in order.
  std::map<int, std::vector<std::array<std::int64_t, 3>>> tiles;
  std::map<int, long> have;
  int current = 0;
  std::vector<Sample> pixels;
  const auto reads_of = [&](int frame) -> const Reads& {
    return reads[static_cast<std::size_t>(schedule.plan(frame).display_level)];
  };
  const auto slot = [](const Reads& rd, int i, int j) {
    const auto cols = static_cast<std::size_t>(rd.range.i1 - rd.range.i0);
    return static_cast<std::size_t>(j - rd.range.j0) * cols +
           static_cast<std::size_t>(i - rd.range.i0);
  };
  // --latency-probe: by frame, when each compositor's band was delivered.
  std::map<int, std::map<int, sc_core::sc_time>> band_delivered;
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kBand) continue;
    if (setup_.journeys) band_delivered[m.frame][m.from - lay.compositor(0)] = last_delivered_;
    const Reads& rd = reads_of(m.frame);
    auto& tile = tiles[m.frame];
    tile.resize(static_cast<std::size_t>(rd.range.i1 - rd.range.i0) *
                static_cast<std::size_t>(rd.range.j1 - rd.range.j0));
    for (const Sample& s : m.samples)
      tile[slot(rd, lattice.i_of(s.index), lattice.j_of(s.index))] = s.sum;
    have[m.frame] += static_cast<long>(m.samples.size());
    while (current < setup_.frames && have[current] >= reads_of(current).positions) {
      const Reads& now = reads_of(current);
      const auto& t = tiles[current];
      const auto at = [&](int i, int j) -> const std::array<std::int64_t, 3>& {
        return t[slot(now, i, j)];
      };
      // SIMD: the whole tile at once, whatever its content (L282): each display pixel from the
      // positions around it on the grid of the level the frame is displayed at.
      const sc_core::sc_time began = clock_.now();
      if (!setup_.bypass.back_end)
        compute_for(tile_time_, "resample", {{"pixels", (x1 - x0) * (y1 - y0)}});
      if (setup_.journeys) probe_tile(current, began, band_delivered[current]);
      band_delivered.erase(current);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          Sample p;
          p.index = static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(lay.width) +
                    static_cast<std::uint32_t>(x);
          p.sum = lattice.resample(x, y, now.step, at);
          pixels.push_back(p);
        }
      send(lay.frame_buffer(), take_samples(Kind::kPixels, current, pixels));
      tiles.erase(current);
      have.erase(current);
      ++current;
    }
  }
}

// --- Frame buffer -------------------------------------------------------------------------

void FrameBuffer::declare_params(params::ParamRegistry& r) {
  modules::ParamDecls(r, kFrameBuffer, false).add(kPixelTime);
  modules::ParamDecls(r, kDisplay, false).add(kDisplayFrame);
}

int FrameBuffer::display_frame(const params::ParamRegistry& r, int frames) {
  const modules::ModuleParams p(r, kDisplay);
  const std::int64_t f = p.get(kDisplayFrame);
  if (f >= frames)
    throw InputError(std::string(kDisplay) + "." + kDisplayFrame.name() + " (set at " +
                         p.where_set(kDisplayFrame.name()) + ")",
                     0,
                     "pxpl5-raytrace: frame " + std::to_string(f) +
                         " is not rendered: the run has " + std::to_string(frames) +
                         " frames (0 to " + std::to_string(frames - 1) + "; -1 for the last)");
  return f < 0 ? frames - 1 : static_cast<int>(f);
}

FrameBuffer::FrameBuffer(sc_core::sc_module_name name, MachineRun& run,
                         modules::RingChannel<Message>& ring, const Setup& setup)
    : RingNode(name, run.trace(), ring, setup.layout.frame_buffer(), setup.sizes),
      run_(run),
      setup_(setup),
      pixel_time_(modules::ModuleParams(run.registry(), kFrameBuffer).get(kPixelTime)) {
  SC_THREAD(run);
}

void FrameBuffer::probe_pixels(const Message& m) {
  using modules::LatencyPart;
  modules::LatencyProbe& probe = run_.probe();
  const auto& st = setup_.stages;
  SampleJourneys& book = *setup_.journeys;
  const auto in = book.to_frame_buffer.find({m.frame, m.from - setup_.layout.renderer(0)});
  if (in == book.to_frame_buffer.end()) return;
  auto& written = book.written[m.frame];
  for (const auto j : in->second.journeys) {
    probe.add(j, st.ring, LatencyPart::kTransfer, last_delivered_ - in->second.sent);
    probe.add(j, st.frame_buffer, LatencyPart::kQueueing, last_taken_ - last_delivered_);
    probe.add(j, st.frame_buffer, LatencyPart::kService, clock_.now() - last_taken_);
    written.emplace_back(j, clock_.now());
  }
  book.to_frame_buffer.erase(in);
}

void FrameBuffer::probe_display(int frame) {
  modules::LatencyProbe& probe = run_.probe();
  SampleJourneys& book = *setup_.journeys;
  const auto w = book.written.find(frame);
  if (w == book.written.end()) return;
  // Written, then waiting for the frame's other tiles (and the frame before) to be displayed.
  for (const auto& [j, at] : w->second) {
    probe.add(j, setup_.stages.frame_buffer, modules::LatencyPart::kQueueing, clock_.now() - at);
    probe.end(j, clock_.now());
  }
  book.written.erase(w);
}

void FrameBuffer::run() {
  functional::FrameState& frame = run_.frame();
  const long all = static_cast<long>(frame.width()) * frame.height();
  // By frame in flight: pixels written. Frames are displayed in order.
  std::map<int, long> have;
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kPixels) continue;
    if (!setup_.bypass.back_end)
      compute_for(modules::times(pixel_time_, m.samples.size()), "write",
                  {{"pixels", m.samples.size()}});
    if (setup_.journeys) probe_pixels(m);
    // The image is the displayed frame's (display.frame, the last by default): its pixels as
    // they arrived.
    if (m.frame == setup_.display_frame)
      for (const Sample& s : m.samples) frame.fb().add_raw(s.index, s.sum);
    have[m.frame] += static_cast<long>(m.samples.size());
    for (auto f = static_cast<int>(displayed_.size()); f < setup_.frames && have[f] >= all;
         f = static_cast<int>(displayed_.size())) {
      displayed_.push_back(clock_.now());
      have.erase(f);
      if (setup_.journeys) probe_display(f);
      Message done;
      done.kind = Kind::kFrameDone;
      done.frame = f;
      send(setup_.layout.host(), std::move(done));
    }
  }
}

}  // namespace rtsim::platform::pxpl5
