// libFuzzer target for the glTF-JSON-structure generator (see fuzz_entry.h, fuzz_structured.cpp).
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    prism::fuzz::FuzzGltfJson(data, size);
    return 0;
}
