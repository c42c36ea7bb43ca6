#pragma once
// Parameters of the Whitted/Hall shading model. The platform fills them from the configuration
// (`shade.*`); defaults are documented in docs/parameters.md.

namespace rtsim::shading {

struct ShadeParams {
  /// Ambient intensity I_a (Phong term R*I_a, seed 000 L414). NFF has no ambient term;
  /// assumption: 0.1, enough to keep shadowed sides readable.
  double ambient = 0.1;
  /// Depth limit of the ray tree (reflection/refraction generations).
  int max_depth = 5;
  /// Hall's adaptive tree depth (seed 001 §4.3.5): a reflected or refracted ray whose
  /// contribution factor falls below this is not spawned. The thesis gives no value;
  /// assumption: 1/255, the smallest step of an 8-bit channel.
  double contribution_threshold = 1.0 / 255.0;
  /// Intensity of each point light. NFF gives only relative colours; 0 means "choose
  /// 1/sqrt(number of lights)" so scenes with many lights do not burn out.
  double light_intensity = 0.0;
  /// Relative size of the offset that moves a spawned ray off its surface, times the magnitude
  /// of the hit point's coordinates plus the scene's extent.
  double offset_relative = 1e-9;
  /// Scene extent (largest side of the bounding box); set by the renderer.
  double scene_extent = 1.0;
};

}  // namespace rtsim::shading
