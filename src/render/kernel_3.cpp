// Kernel masks 5, 7, 13, 15, 21, 23, 29, 31 (render/kernel.h): the kernels are instantiated over
// four files so that they compile in parallel.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(5u)
PRISM_INSTANTIATE_KERNEL(7u)
PRISM_INSTANTIATE_KERNEL(13u)
PRISM_INSTANTIATE_KERNEL(15u)
PRISM_INSTANTIATE_KERNEL(21u)
PRISM_INSTANTIATE_KERNEL(23u)
PRISM_INSTANTIATE_KERNEL(29u)
PRISM_INSTANTIATE_KERNEL(31u)

}  // namespace prism
