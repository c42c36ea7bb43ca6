#include "platform/machines/pxpl5_raytrace/nodes.hpp"

#include <algorithm>
#include <numeric>

#include "firmware/tasks/lattice_ray_task.hpp"
#include "firmware/tasks/region_sampling.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::pxpl5 {

std::uint64_t WireSizes::bytes(const Message& m) const {
  switch (m.kind) {
    case Kind::kSamples:
    case Kind::kBand:
      return header + sample * m.samples.size();
    case Kind::kPixels:
      return header + pixel * m.samples.size();
    default:
      return control;
  }
}

// --- Host ---------------------------------------------------------------------------------

Host::Host(sc_core::sc_module_name name, MachineTrace& trace, modules::RingChannel<Message>& ring,
           Context& ctx)
    : RingNode(name, trace, ring, ctx.layout.host(), ctx.sizes), ctx_(ctx) {
  SC_THREAD(run);
}

void Host::run() {
  for (int f = 0; f < ctx_.frames; ++f) {
    started_.push_back(clock_.now());
    Message start;
    start.kind = Kind::kStartFrame;
    start.frame = f;
    send(ctx_.layout.master(), std::move(start));
    for (;;) {
      const Message m = receive(Wait::kData);
      if (m.kind == Kind::kFrameDone && m.frame == f) break;
    }
    done_.push_back(clock_.now());
    if (ctx_.opts && ctx_.opts->progress) ctx_.opts->progress(f + 1, ctx_.frames);
  }
}

// --- Master GP ----------------------------------------------------------------------------

MasterGp::MasterGp(sc_core::sc_module_name name, MachineTrace& trace,
                   modules::RingChannel<Message>& ring, Context& ctx,
                   const sc_core::sc_time& assign_time)
    : RingNode(name, trace, ring, ctx.layout.master(), ctx.sizes),
      ctx_(ctx),
      assign_time_(assign_time) {
  set_timing(ctx.gp_timing);
  SC_THREAD(run);
}

void MasterGp::assign(int caster) {
  if (!ctx_.bypass_master) compute_for(assign_time_, "assign", {{"caster", caster}});
  Message a;
  a.kind = Kind::kAssign;
  a.frame = frame_;
  a.region = regions_[next_++];
  ++assignments_;
  send(caster, std::move(a));
}

void MasterGp::run() {
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind == Kind::kStartFrame) {
      frame_ = m.frame;
      regions_ = ctx_.layout.regions();
      // A sampled frame: the detailed regions only (the others were cast functionally).
      if (ctx_.sample)
        std::erase_if(regions_, [&](const Region& g) { return !ctx_.sample->detailed_unit(g.id); });
      cost_.resize(regions_.size(), 0.0);
      // 0th-order cost prediction (L360): the costliest of the previous frame first.
      if (ctx_.cost_order && frame_ > 0)
        std::stable_sort(regions_.begin(), regions_.end(), [&](const Region& a, const Region& b) {
          return cost_[static_cast<std::size_t>(a.id)] > cost_[static_cast<std::size_t>(b.id)];
        });
      next_ = 0;
      std::vector<int> waiting;
      waiting.swap(waiting_);
      for (int c : waiting) {
        if (next_ < regions_.size())
          assign(c);
        else
          waiting_.push_back(c);
      }
      continue;
    }
    if (m.kind != Kind::kRequest) continue;
    if (m.last_region >= 0 && static_cast<std::size_t>(m.last_region) < cost_.size())
      cost_[static_cast<std::size_t>(m.last_region)] = m.last_cost_s;
    // First come, first served (L352); a request after the frame's last region waits for the
    // next frame.
    if (frame_ >= 0 && next_ < regions_.size())
      assign(m.from);
    else
      waiting_.push_back(m.from);
  }
}

// --- Ray caster ---------------------------------------------------------------------------

RayCaster::RayCaster(sc_core::sc_module_name name, MachineTrace& trace,
                     modules::RingChannel<Message>& ring, Context& ctx, int number)
    : RingNode(name, trace, ring, ctx.layout.caster(number), ctx.sizes),
      ctx_(ctx),
      shade_(*ctx.scene, ctx.shade) {
  set_timing(ctx.gp_timing);
  SC_THREAD(run);
}

void RayCaster::run() {
  Message request;
  request.kind = Kind::kRequest;
  send(ctx_.layout.master(), request);
  const Layout& lay = ctx_.layout;
  const tasks::SampleLattice lattice = lay.lattice();
  const int spp = ctx_.frame->spp();
  TraceCounters& counters = ctx_.frame->counters();
  tasks::LatticeRayTask task(*ctx_.tracer, shade_, counters);
  std::vector<std::vector<Sample>> by_compositor(static_cast<std::size_t>(lay.compositors));
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kAssign) continue;
    const sc_core::sc_time began = clock_.now();
    const Region& g = m.region;
    const bool last_frame = m.frame == ctx_.frames - 1;
    const shading::PinholeCamera& camera = ctx_.cameras[static_cast<std::size_t>(m.frame)];
    const Cost before = counters.cost;
    const auto cast = [&](int i, int j) {
      if (ctx_.bypass_casters) {
        Sample none;  // by-pass code: the message, no ray (L333)
        none.index = lattice.index(i, j);
        return none;
      }
      const std::int64_t pixel = last_frame ? lattice.pixel(i, j) : -1;
      if (pixel >= 0) ++cast_last_frame_;
      return task.cast(camera, lattice, i, j, spp, [&](bool found, const Hit& hit) {
        if (pixel < 0) return;
        covered_last_frame_ += found;
        ctx_.frame->record_primary(static_cast<std::uint32_t>(pixel), found, hit);
      });
    };
    const auto update = [&](int i, int j) {
      return tasks::updated_in_frame(i, j, m.frame, lay.update_period);
    };
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
    if (!ctx_.bypass_casters)
      compute(spent, "region", {{"region", g.id}, {"pixels", g.w * g.h}, {"rays", rays}});
    ++regions_;
    // The samples go to the compositors owning their rows (L310).
    for (int k = 0; k < lay.compositors; ++k) {
      auto& samples = by_compositor[static_cast<std::size_t>(k)];
      if (samples.empty()) continue;
      Message out_msg = take_samples(Kind::kSamples, m.frame, samples);
      out_msg.began = began;
      out_msg.sent = clock_.now();
      if (++ctx_.samples_messages == ctx_.corrupt_samples) {
        // The fault: the first sample turns black, or white if it was black.
        auto& sum = out_msg.samples.front().sum;
        const bool black = sum[0] == 0 && sum[1] == 0 && sum[2] == 0;
        const std::int64_t v =
            black ? static_cast<std::int64_t>(shading::PixelAccumulator::kScale) * spp : 0;
        sum = {v, v, v};
      }
      send(lay.compositor(k), std::move(out_msg));
    }
    if (ctx_.sample) ctx_.sample->unit_done(g.id, began.value(), clock_.now().value());
    Message next;
    next.kind = Kind::kRequest;
    next.frame = m.frame;
    next.last_region = g.id;
    next.last_cost_s = (clock_.now() - began).to_seconds();
    send(lay.master(), std::move(next));
  }
}

// --- Compositor ---------------------------------------------------------------------------

Compositor::Compositor(sc_core::sc_module_name name, MachineTrace& trace,
                       modules::RingChannel<Message>& ring, Context& ctx, int number,
                       const sc_core::sc_time& sample_time)
    : RingNode(name, trace, ring, ctx.layout.compositor(number), ctx.sizes),
      ctx_(ctx),
      number_(number),
      sample_time_(sample_time) {
  set_timing(ctx.gp_timing);
  const Layout& lay = ctx.layout;
  const std::vector<Region> regions = lay.regions();
  for (int phase = 0; phase <= lay.update_period; ++phase) {
    // Phase 0 is the first frame; phase p > 0 any frame f > 0 with f mod period = p - 1.
    const int frame = phase == 0 ? 0 : lay.update_period + phase - 1;
    long n = 0;
    for (const Region& g : regions) n += lay.positions_sent(g, number, frame);
    expected_.push_back(n);
  }
  SC_THREAD(run);
}

void Compositor::probe_samples(const Message& m) {
  modules::LatencyProbe* probe = ctx_.probe;
  if (!probe || !probe->enabled()) return;
  using modules::LatencyPart;
  const auto& st = ctx_.stages;
  // Every sample of the message went the same way: the region's cast (its samples are done
  // together), the ring (waiting for the token and carried), the inbox, the compositing.
  for (std::size_t k = 0; k < m.samples.size(); ++k) {
    const auto j = probe->begin(m.began);
    probe->add(j, st.caster, LatencyPart::kService, m.sent - m.began);
    probe->add(j, st.ring, LatencyPart::kTransfer, last_delivered_ - m.sent);
    probe->add(j, st.inbox, LatencyPart::kQueueing, last_taken_ - last_delivered_);
    probe->add(j, st.compositor, LatencyPart::kService, clock_.now() - last_taken_);
    probe->end(j, clock_.now());
  }
}

long Compositor::expected(int frame) const {
  const int phase = frame == 0 ? 0 : 1 + frame % ctx_.layout.update_period;
  return expected_[static_cast<std::size_t>(phase)];
}

void Compositor::run() {
  const Layout& lay = ctx_.layout;
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
  std::vector<int> written(kept.size(), -1);  // the frame each position was last written in
  const auto tile_cols = lay.tiles_reading(false), tile_rows = lay.tiles_reading(true);
  std::vector<std::vector<Sample>> by_renderer(static_cast<std::size_t>(lay.renderers()));
  const auto keep = [&](const Sample& s, int frame) {
    const int j = lattice.j_of(s.index), i = lattice.i_of(s.index);
    const std::size_t k = static_cast<std::size_t>(local_row[static_cast<std::size_t>(j)]) * nx +
                          static_cast<std::size_t>(i);
    tasks::keep_copy(kept[k], written[k], s, frame);
  };
  long have = 0;
  // A sampled frame: the regions not simulated in detail are here from the start.
  if (!ctx_.functional_samples.empty())
    for (const Sample& s : ctx_.functional_samples[static_cast<std::size_t>(number_)]) {
      keep(s, 0);
      ++have;
    }
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kSamples) continue;
    if (!ctx_.bypass_back_end)
      compute_for(modules::times(sample_time_, m.samples.size()), "composite",
                  {{"samples", m.samples.size()}});
    probe_samples(m);
    for (const Sample& s : m.samples) keep(s, m.frame);
    samples_ += m.samples.size();
    have += static_cast<long>(m.samples.size());
    if (have < expected(m.frame)) continue;
    // Its bands have the frame: each renderer gets the positions its tile reads.
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (std::size_t i = 0; i < nx; ++i) {
        const Sample& s = kept[r * nx + i];
        for (int ty : tile_rows[static_cast<std::size_t>(rows[r])])
          for (int tx : tile_cols[i])
            by_renderer[static_cast<std::size_t>(ty * lay.tiles_x() + tx)].push_back(s);
      }
    for (int k = 0; k < lay.renderers(); ++k) {
      auto& part = by_renderer[static_cast<std::size_t>(k)];
      if (!part.empty()) send(lay.renderer(k), take_samples(Kind::kBand, m.frame, part));
    }
    have = 0;
  }
}

// --- Renderer -----------------------------------------------------------------------------

Renderer::Renderer(sc_core::sc_module_name name, MachineTrace& trace,
                   modules::RingChannel<Message>& ring, Context& ctx, int number,
                   const sc_core::sc_time& tile_time)
    : RingNode(name, trace, ring, ctx.layout.renderer(number), ctx.sizes),
      ctx_(ctx),
      number_(number),
      tile_time_(tile_time) {
  SC_THREAD(run);
}

void Renderer::run() {
  const Layout& lay = ctx_.layout;
  const tasks::SampleLattice lattice = lay.lattice();
  const tasks::LatticeRange r = lay.lattice_of_renderer(number_);
  const int cols = r.i1 - r.i0;
  const long mine = static_cast<long>(cols) * (r.j1 - r.j0);
  std::vector<std::array<std::int64_t, 3>> tile(static_cast<std::size_t>(mine));
  const auto at = [&](int i, int j) -> std::array<std::int64_t, 3>& {
    return tile[static_cast<std::size_t>(j - r.j0) * static_cast<std::size_t>(cols) +
                static_cast<std::size_t>(i - r.i0)];
  };
  const int tx = number_ % lay.tiles_x(), ty = number_ / lay.tiles_x();
  const int x0 = tx * lay.tile, y0 = ty * lay.tile;
  const int x1 = std::min(x0 + lay.tile, lay.width), y1 = std::min(y0 + lay.tile, lay.height);
  long have = 0;
  std::vector<Sample> pixels;
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kBand) continue;
    for (const Sample& s : m.samples) {
      at(lattice.i_of(s.index), lattice.j_of(s.index)) = s.sum;
    }
    have += static_cast<long>(m.samples.size());
    if (have < mine) continue;
    have = 0;
    // SIMD: the whole tile at once, whatever its content (L282): each display pixel from the
    // lattice positions around it.
    if (!ctx_.bypass_back_end)
      compute_for(tile_time_, "resample", {{"pixels", (x1 - x0) * (y1 - y0)}});
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        Sample p;
        p.index = static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(lay.width) +
                  static_cast<std::uint32_t>(x);
        p.sum = lattice.resample(x, y, at);
        pixels.push_back(p);
      }
    send(lay.frame_buffer(), take_samples(Kind::kPixels, m.frame, pixels));
  }
}

// --- Frame buffer -------------------------------------------------------------------------

FrameBuffer::FrameBuffer(sc_core::sc_module_name name, MachineTrace& trace,
                         modules::RingChannel<Message>& ring, Context& ctx,
                         const sc_core::sc_time& pixel_time)
    : RingNode(name, trace, ring, ctx.layout.frame_buffer(), ctx.sizes),
      ctx_(ctx),
      pixel_time_(pixel_time) {
  SC_THREAD(run);
}

void FrameBuffer::run() {
  const long all = static_cast<long>(ctx_.frame->width()) * ctx_.frame->height();
  long have = 0;
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kPixels) continue;
    if (!ctx_.bypass_back_end)
      compute_for(modules::times(pixel_time_, m.samples.size()), "write",
                  {{"pixels", m.samples.size()}});
    // The image is the last frame's: the pixels as they arrived.
    if (m.frame == ctx_.frames - 1)
      for (const Sample& s : m.samples) ctx_.frame->fb().add_raw(s.index, s.sum);
    have += static_cast<long>(m.samples.size());
    if (have < all) continue;
    have = 0;
    Message done;
    done.kind = Kind::kFrameDone;
    done.frame = m.frame;
    send(ctx_.layout.host(), std::move(done));
  }
}

}  // namespace rtsim::platform::pxpl5
