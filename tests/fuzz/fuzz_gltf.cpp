// libFuzzer target for the gltf reader (see fuzz_entry.h).
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    prism::fuzz::FuzzGltf(data, size);
    return 0;
}
