#include "platform/machines/pixelflow/pass_plan.hpp"

#include "firmware/raster/appearance.hpp"
#include "platform/machines/pixelflow/functional_passes.hpp"

namespace rtsim::platform::pixelflow {

std::string Pass::name() const {
  switch (kind) {
    case PassKind::Shadow:
      return "shadow" + std::to_string(light);
    case PassKind::Reflection:
      return "reflection";
    case PassKind::Camera:
      break;
  }
  return "camera";
}

int Pass::bytes_per_pixel() const { return depth_only() ? 4 : raster::kAppearanceBytes; }

std::vector<int> PassPlan::map_passes() const {
  std::vector<int> out;
  for (std::size_t i = 0; i < passes.size(); ++i)
    if (passes[i].kind != PassKind::Camera) out.push_back(static_cast<int>(i));
  return out;
}

const Pass* PassPlan::camera() const {
  for (const auto& p : passes)
    if (p.kind == PassKind::Camera) return &p;
  return nullptr;
}

namespace {

Pass make_pass(PassKind kind, const raster::ViewTransform& view, raster::ViewSetup setup,
               int samples, int rasterizers) {
  Pass p;
  p.kind = kind;
  p.view = view;
  p.setup = std::move(setup);
  p.grid = {view.width, view.height};
  p.samples = samples;
  const auto bins = bin_by_region(p.setup, p.grid);
  p.shares.resize(bins.size());
  for (std::size_t r = 0; r < bins.size(); ++r) {
    p.shares[r].resize(static_cast<std::size_t>(rasterizers));
    for (const std::uint32_t i : bins[r])
      p.shares[r][p.setup.triangles[i].triangle % static_cast<std::uint32_t>(rasterizers)]
          .push_back(i);
  }
  return p;
}

}  // namespace

PassPlan plan_passes(const FrameSetup& f, int rasterizers) {
  PassPlan plan;
  plan.rasterizers = rasterizers;
  for (std::size_t l = 0; l < f.shadow_views.size(); ++l) {
    const auto& view = f.shadow_views[l];
    plan.passes.push_back(make_pass(PassKind::Shadow, view,
                                    raster::set_up_view(f.mesh, view, f.words), 1, rasterizers));
    plan.passes.back().light = static_cast<int>(l);
  }
  if (f.mirror)
    plan.passes.push_back(make_pass(
        PassKind::Reflection, f.mirror->view,
        raster::set_up_view(f.mesh, f.mirror->view, f.words, f.mirror->include, f.mirror->plane), 1,
        rasterizers));
  plan.passes.push_back(make_pass(PassKind::Camera, f.camera,
                                  raster::set_up_view(f.mesh, f.camera, f.words), f.spp,
                                  rasterizers));
  return plan;
}

}  // namespace rtsim::platform::pixelflow
