// The general kernel, Kernel<KernelGeneral> (render/kernel.h): BSDFs and specular recursion.
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(KernelGeneral)

}  // namespace prism
