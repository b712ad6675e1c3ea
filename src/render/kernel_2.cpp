// Kernel masks 1, 3, 9, 11, 17, 19, 25, 27 (render/kernel.h): the kernels are instantiated over
// four files so that they compile in parallel.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(1u)
PRISM_INSTANTIATE_KERNEL(3u)
PRISM_INSTANTIATE_KERNEL(9u)
PRISM_INSTANTIATE_KERNEL(11u)
PRISM_INSTANTIATE_KERNEL(17u)
PRISM_INSTANTIATE_KERNEL(19u)
PRISM_INSTANTIATE_KERNEL(25u)
PRISM_INSTANTIATE_KERNEL(27u)

}  // namespace prism
