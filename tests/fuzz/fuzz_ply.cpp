// libFuzzer target for the ply reader (see fuzz_entry.h).
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    prism::fuzz::FuzzPly(data, size);
    return 0;
}
