// libFuzzer target for the pbrt reader (see fuzz_entry.h).
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    prism::fuzz::FuzzPbrt(data, size);
    return 0;
}
