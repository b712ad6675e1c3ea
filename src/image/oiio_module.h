// The C-style interface between Prism's image module and libprism_oiio.so, the shared module
// that wraps OpenImageIO. OpenImageIO (and the ~260 libraries Debian's build of it links) is
// loaded with dlopen() the first time an image needs it, so processes that read no image
// through it never pay for resolving those libraries at start-up. Only plain C types cross the
// boundary; errors are copied into a caller-provided buffer.
#pragma once

#include <cstddef>

extern "C" {

// Bumped whenever this struct or a signature changes; the loader rejects other versions.
#define PRISM_OIIO_MODULE_VERSION 2

struct PrismOiioSpec {
    int width, height, depth, nchannels;
    int alphaChannel;  // -1 when there is none
    int isFloat;       // the file stores floating-point values (EXR, HDR, PFM, float TIFF)
    int isUint8;       // the file stores 8-bit values
    int deep;          // deep (multi-sample) image
};

// An opened image (plus the in-memory reader it may read from); opaque to the caller.
typedef struct PrismOiioInput PrismOiioInput;

struct PrismOiioModule {
    int version;  // PRISM_OIIO_MODULE_VERSION
    // Opens a file, or an encoded image in memory whose `name` ends in the format's extension;
    // the memory must outlive the returned input. `tryAllReaders` = 0 tries only the reader the
    // extension names. Returns null and fills `err` on failure.
    PrismOiioInput *(*openFile)(const char *path, int tryAllReaders, char *err, size_t errSize);
    PrismOiioInput *(*openMemory)(const unsigned char *data, size_t size, const char *name,
                                  int tryAllReaders, char *err, size_t errSize);
    void (*getSpec)(const PrismOiioInput *in, PrismOiioSpec *spec);
    // Reads channels [0, nchannels) of the whole image as interleaved float. Returns 0 on failure.
    int (*readFloat)(PrismOiioInput *in, int nchannels, float *out, char *err, size_t errSize);
    void (*close)(PrismOiioInput *in);
    // Encodes width x height x channels values (float when isFloat, else uint8), top row
    // first, straight alpha in channel `alphaChannel` (-1: none), in memory, and hands the
    // encoded file to `sink` (which returns 0 when it could not store it). No file is opened:
    // the format follows the extension of `name`. `colorSpace` ("Linear" or "sRGB") and
    // `compression` (may be empty) are passed to OpenImageIO as they are. Returns 0 on
    // failure (`err` filled unless the sink failed).
    int (*write)(const char *name, int width, int height, int channels, int alphaChannel,
                 int isFloat, const void *data, const char *colorSpace, const char *compression,
                 int (*sink)(void *ctx, const unsigned char *bytes, size_t size), void *sinkCtx,
                 char *err, size_t errSize);
};

// The module's one exported symbol.
#define PRISM_OIIO_MODULE_ENTRY "PrismOiioModuleEntry"
typedef const PrismOiioModule *(*PrismOiioModuleEntryFn)(void);

}  // extern "C"
