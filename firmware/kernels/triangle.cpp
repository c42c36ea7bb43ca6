// The triangle kernel is a template (double for the renderer, float to model 32-bit hardware);
// both precisions are instantiated once here.
#include "firmware/kernels/triangle.hpp"

namespace rtsim::kernels {

template class TriangleKernelT<double>;
template class TriangleKernelT<float>;

}  // namespace rtsim::kernels
