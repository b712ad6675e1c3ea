// Kernel masks 0, 16, 32, 33, 34, 42, 48, 49, 50, 58 (render/kernel.h): the 40 instantiated masks
// are spread over four files so that they compile in parallel.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(0u)
PRISM_INSTANTIATE_KERNEL(16u)
PRISM_INSTANTIATE_KERNEL(32u)
PRISM_INSTANTIATE_KERNEL(33u)
PRISM_INSTANTIATE_KERNEL(34u)
PRISM_INSTANTIATE_KERNEL(42u)
PRISM_INSTANTIATE_KERNEL(48u)
PRISM_INSTANTIATE_KERNEL(49u)
PRISM_INSTANTIATE_KERNEL(50u)
PRISM_INSTANTIATE_KERNEL(58u)

}  // namespace prism
