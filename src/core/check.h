// CHECK-style assertions for programmer errors only (never for scene data).
#pragma once

#include <cstdio>
#include <cstdlib>

#define PRISM_CHECK(cond)                                                                 \
    do {                                                                                  \
        if (!(cond)) {                                                                    \
            std::fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            std::abort();                                                                 \
        }                                                                                 \
    } while (0)

#ifdef NDEBUG
#define PRISM_DCHECK(cond) ((void)0)
#else
#define PRISM_DCHECK(cond) PRISM_CHECK(cond)
#endif
