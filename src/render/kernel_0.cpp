// Kernel masks 0, 2, 8, 10, 16, 18, 24, 26 (render/kernel.h): the kernels are instantiated over
// four files so that they compile in parallel.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(0u)
PRISM_INSTANTIATE_KERNEL(2u)
PRISM_INSTANTIATE_KERNEL(8u)
PRISM_INSTANTIATE_KERNEL(10u)
PRISM_INSTANTIATE_KERNEL(16u)
PRISM_INSTANTIATE_KERNEL(18u)
PRISM_INSTANTIATE_KERNEL(24u)
PRISM_INSTANTIATE_KERNEL(26u)

}  // namespace prism
