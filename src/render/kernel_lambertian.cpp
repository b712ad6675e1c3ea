// The Lambertian kernel, Kernel<0> (render/kernel.h): every material Lambertian matte.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(0u)

}  // namespace prism
