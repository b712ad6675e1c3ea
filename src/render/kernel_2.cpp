// Kernel masks 8, 24, 38, 40, 41, 46, 54, 56, 57, 62 (render/kernel.h): the 40 instantiated masks
// are spread over four files so that they compile in parallel.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(8u)
PRISM_INSTANTIATE_KERNEL(24u)
PRISM_INSTANTIATE_KERNEL(38u)
PRISM_INSTANTIATE_KERNEL(40u)
PRISM_INSTANTIATE_KERNEL(41u)
PRISM_INSTANTIATE_KERNEL(46u)
PRISM_INSTANTIATE_KERNEL(54u)
PRISM_INSTANTIATE_KERNEL(56u)
PRISM_INSTANTIATE_KERNEL(57u)
PRISM_INSTANTIATE_KERNEL(62u)

}  // namespace prism
