// The BSDF kernel without specular recursion, Kernel<KernelBsdf> (render/kernel.h).
#include "render/kernel_impl.h"

namespace prism {

PRISM_INSTANTIATE_KERNEL(KernelBsdf)

}  // namespace prism
