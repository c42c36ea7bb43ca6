#include "firmware/kernels/bezier_wang.hpp"

namespace rtsim::kernels {

// The two precisions the project uses: float as the paper's TMS320C6701 DSPs (seed 002 L296),
// double as the functional renderer.
template WangResult<float> wang_intersect<float>(const ControlNet<float>&, const Vec3T<float>&,
                                                 const Vec3T<float>&, int, WangCounters*,
                                                 const CullerConfig&, const FixedWords*);
template WangResult<double> wang_intersect<double>(const ControlNet<double>&, const Vec3T<double>&,
                                                   const Vec3T<double>&, int, WangCounters*,
                                                   const CullerConfig&, const FixedWords*);

}  // namespace rtsim::kernels
