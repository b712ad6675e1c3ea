// libFuzzer target for the image reader (see fuzz_entry.h).
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    prism::fuzz::FuzzImage(data, size);
    return 0;
}
