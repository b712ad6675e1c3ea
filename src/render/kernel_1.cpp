// Kernel masks 4, 6, 12, 14, 20, 22, 28, 30 (render/kernel.h): the kernels are instantiated over
// four files so that they compile in parallel.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(4u)
PRISM_INSTANTIATE_KERNEL(6u)
PRISM_INSTANTIATE_KERNEL(12u)
PRISM_INSTANTIATE_KERNEL(14u)
PRISM_INSTANTIATE_KERNEL(20u)
PRISM_INSTANTIATE_KERNEL(22u)
PRISM_INSTANTIATE_KERNEL(28u)
PRISM_INSTANTIATE_KERNEL(30u)

}  // namespace prism
