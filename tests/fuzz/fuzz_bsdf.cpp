// libFuzzer target for the .bsdf reader of Material "fourier" (see fuzz_entry.h).
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    prism::fuzz::FuzzBsdf(data, size);
    return 0;
}
