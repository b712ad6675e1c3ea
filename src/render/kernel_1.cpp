// Kernel masks 4, 20, 35, 36, 37, 43, 51, 52, 53, 59 (render/kernel.h): the 40 instantiated masks
// are spread over four files so that they compile in parallel.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(4u)
PRISM_INSTANTIATE_KERNEL(20u)
PRISM_INSTANTIATE_KERNEL(35u)
PRISM_INSTANTIATE_KERNEL(36u)
PRISM_INSTANTIATE_KERNEL(37u)
PRISM_INSTANTIATE_KERNEL(43u)
PRISM_INSTANTIATE_KERNEL(51u)
PRISM_INSTANTIATE_KERNEL(52u)
PRISM_INSTANTIATE_KERNEL(53u)
PRISM_INSTANTIATE_KERNEL(59u)

}  // namespace prism
