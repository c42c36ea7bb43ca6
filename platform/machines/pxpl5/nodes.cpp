#include "platform/machines/pxpl5/nodes.hpp"

#include <algorithm>
#include <numeric>

#include "firmware/tasks/ray_tree.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
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
      regions_ = ctx_.layout.regions(ctx_.scheme, ctx_.square);
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
  const int w = ctx_.frame->width(), h = ctx_.frame->height(), spp = ctx_.frame->spp();
  std::vector<shading::TracedRay> stack, spawned;
  std::vector<std::vector<Sample>> by_compositor(static_cast<std::size_t>(lay.compositors));
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kAssign) continue;
    const sc_core::sc_time began = clock_.now();
    const Region& g = m.region;
    const bool last_frame = m.frame == ctx_.frames - 1;
    const shading::PinholeCamera& camera = ctx_.cameras[static_cast<std::size_t>(m.frame)];
    TraceCounters& counters = ctx_.frame->counters();
    const Cost before = counters.cost;
    for (int y = g.y0; y < g.y0 + g.h && ctx_.bypass_casters; ++y)
      for (int x = g.x0; x < g.x0 + g.w; ++x) {
        by_compositor[static_cast<std::size_t>(lay.compositor_of_row(y))].push_back(
            {static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(w) +
                 static_cast<std::uint32_t>(x),
             {}});
        ++samples_;
      }
    for (int y = g.y0; y < g.y0 + g.h && !ctx_.bypass_casters; ++y) {
      const auto row = static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(w);
      tasks::VisionRayTask vision(camera, w, h, spp, row + static_cast<std::uint32_t>(g.x0),
                                  row + static_cast<std::uint32_t>(g.x0 + g.w));
      for (int x = g.x0; x < g.x0 + g.w; ++x) {
        const std::uint32_t pixel = row + static_cast<std::uint32_t>(x);
        for (int s = 0; s < spp; ++s) {
          int sample = 0;
          bool first = true;
          tasks::trace_ray_tree(vision.next(sample), *ctx_.tracer, shade_, *ctx_.scratch, counters,
                                stack, spawned,
                                [&](const shading::TracedRay& r, bool found, const Hit& hit) {
                                  if (first && sample == 0 && last_frame)
                                    ctx_.frame->record_primary(r.pixel, found, hit);
                                  first = false;
                                });
        }
        by_compositor[static_cast<std::size_t>(lay.compositor_of_row(y))].push_back(
            {pixel, ctx_.scratch->raw(pixel)});
        ctx_.scratch->clear(pixel);
        ++samples_;
      }
    }
    Cost spent = counters.cost;
    spent -= before;
    if (!ctx_.bypass_casters) compute(spent, "region", {{"region", g.id}, {"pixels", g.w * g.h}});
    ++regions_;
    // The samples go to the compositors owning their rows (L310).
    for (int k = 0; k < lay.compositors; ++k) {
      auto& samples = by_compositor[static_cast<std::size_t>(k)];
      if (samples.empty()) continue;
      Message out = take_samples(Kind::kSamples, m.frame, samples);
      if (++ctx_.samples_messages == ctx_.corrupt_samples) {
        // The fault: the first sample turns black, or white if it was black.
        auto& sum = out.samples.front().sum;
        const bool black = sum[0] == 0 && sum[1] == 0 && sum[2] == 0;
        const std::int64_t v =
            black ? static_cast<std::int64_t>(shading::PixelAccumulator::kScale) * spp : 0;
        sum = {v, v, v};
      }
      send(lay.compositor(k), std::move(out));
    }
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
  SC_THREAD(run);
}

void Compositor::run() {
  const Layout& lay = ctx_.layout;
  const long mine = lay.pixels_of_compositor(number_);
  std::vector<std::vector<Sample>> by_renderer(static_cast<std::size_t>(lay.renderers()));
  long have = 0;
  const int w = ctx_.frame->width();
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kSamples) continue;
    if (!ctx_.bypass_back_end)
      compute_for(modules::times(sample_time_, m.samples.size()), "composite",
                  {{"samples", m.samples.size()}});
    for (const Sample& s : m.samples) {
      const int x = static_cast<int>(s.pixel % static_cast<std::uint32_t>(w));
      const int y = static_cast<int>(s.pixel / static_cast<std::uint32_t>(w));
      by_renderer[static_cast<std::size_t>(lay.renderer_of(x, y))].push_back(s);
    }
    samples_ += m.samples.size();
    have += static_cast<long>(m.samples.size());
    if (have < mine) continue;
    // Its bands are complete: each renderer gets the part in its tile.
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
  const long mine = ctx_.layout.pixels_of_renderer(number_);
  std::vector<Sample> tile;
  for (;;) {
    const Message m = receive(Wait::kWork);
    if (m.kind != Kind::kBand) continue;
    tile.insert(tile.end(), m.samples.begin(), m.samples.end());
    if (static_cast<long>(tile.size()) < mine) continue;
    // SIMD: the whole tile at once, whatever its content. One sample a pixel: resampling
    // leaves the values as they are.
    if (!ctx_.bypass_back_end) compute_for(tile_time_, "resample", {{"pixels", tile.size()}});
    send(ctx_.layout.frame_buffer(), take_samples(Kind::kPixels, m.frame, tile));
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
      for (const Sample& s : m.samples) ctx_.frame->fb().add_raw(s.pixel, s.sum);
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
