// libFuzzer target for the STL reader (see fuzz_entry.h).
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    prism::fuzz::FuzzStl(data, size);
    return 0;
}
