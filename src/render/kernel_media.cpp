// The kernel of scenes with participating media, KernelMediaMask (render/kernel.h): the
// general kernel with media compiled in, one instantiation in its own file.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(KernelMediaMask)

}  // namespace prism
