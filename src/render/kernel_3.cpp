// Kernel masks 12, 28, 39, 44, 45, 47, 55, 60, 61, 63 (render/kernel.h): the 40 instantiated masks
// are spread over four files so that they compile in parallel.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(12u)
PRISM_INSTANTIATE_KERNEL(28u)
PRISM_INSTANTIATE_KERNEL(39u)
PRISM_INSTANTIATE_KERNEL(44u)
PRISM_INSTANTIATE_KERNEL(45u)
PRISM_INSTANTIATE_KERNEL(47u)
PRISM_INSTANTIATE_KERNEL(55u)
PRISM_INSTANTIATE_KERNEL(60u)
PRISM_INSTANTIATE_KERNEL(61u)
PRISM_INSTANTIATE_KERNEL(63u)

}  // namespace prism
