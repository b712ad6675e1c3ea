// Finds and opens libprism_oiio.so (OpenImageIO behind a C table) the first time it is needed.
#pragma once

#include "image/oiio_module.h"

namespace prism {

// The module, loaded on first call (thread-safe). Search order: $PRISM_OIIO_MODULE if set (and
// nothing else), then libprism_oiio.so next to the running executable, then the path the build
// tree put it at (for the test executables in build/tests/...). Throws std::runtime_error with
// the paths tried and dlopen's reason when it cannot be loaded; later calls throw the same.
const PrismOiioModule &OiioModule();

// True when the module has already been loaded into this process (for tests).
bool OiioModuleLoaded();

}  // namespace prism
