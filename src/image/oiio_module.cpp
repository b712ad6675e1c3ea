// libprism_oiio.so: the only code in Prism that uses OpenImageIO, behind the C table declared
// in oiio_module.h. Built as a shared module and opened at first use by oiio_loader.cpp.
#include "image/oiio_module.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

struct PrismOiioInput {
    std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy;  // null when reading a file
    std::unique_ptr<OIIO::ImageInput> in;
};

namespace {

void CopyError(const std::string &msg, char *err, size_t errSize) {
    if (!err || errSize == 0) return;
    size_t n = std::min(msg.size(), errSize - 1);
    std::memcpy(err, msg.data(), n);
    err[n] = '\0';
}

// OIIO keeps error messages per object and globally; fetch whichever is set (this also clears
// them, so OIIO does not print them on destruction) and keep the first line only.
template <typename T>
void ReportError(T *obj, char *err, size_t errSize) {
    std::string msg = obj ? obj->geterror() : std::string();
    if (msg.empty()) msg = OIIO::geterror();
    if (msg.empty()) msg = "unknown error";
    size_t nl = msg.find('\n');
    if (nl != std::string::npos) msg.resize(nl);
    CopyError(msg, err, errSize);
}

void SetTryAllReaders(int on) {
    static int current = -1;
    if (current != on) {
        OIIO::attribute("try_all_readers", on);
        current = on;
    }
}

// Ask for unassociated alpha: PNG/TGA store straight alpha and the sRGB decode must apply to
// the stored colour, not to colour premultiplied by alpha.
OIIO::ImageSpec ReadConfig() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

PrismOiioInput *OpenFile(const char *path, int tryAllReaders, char *err, size_t errSize) {
    try {
        SetTryAllReaders(tryAllReaders);
        OIIO::ImageSpec config = ReadConfig();
        auto in = OIIO::ImageInput::open(path, &config);
        if (!in) {
            ReportError(static_cast<OIIO::ImageInput *>(nullptr), err, errSize);
            return nullptr;
        }
        auto *h = new PrismOiioInput;
        h->in = std::move(in);
        return h;
    } catch (const std::exception &e) {
        CopyError(e.what(), err, errSize);
        return nullptr;
    }
}

PrismOiioInput *OpenMemory(const unsigned char *data, size_t size, const char *name,
                           int tryAllReaders, char *err, size_t errSize) {
    try {
        SetTryAllReaders(tryAllReaders);
        auto h = std::make_unique<PrismOiioInput>();
        h->proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(data, size);
        OIIO::ImageSpec config = ReadConfig();
        h->in = OIIO::ImageInput::open(name, &config, h->proxy.get());
        if (!h->in) {
            ReportError(static_cast<OIIO::ImageInput *>(nullptr), err, errSize);
            return nullptr;
        }
        return h.release();
    } catch (const std::exception &e) {
        CopyError(e.what(), err, errSize);
        return nullptr;
    }
}

void GetSpec(const PrismOiioInput *h, PrismOiioSpec *spec) {
    const OIIO::ImageSpec &s = h->in->spec();
    spec->width = s.width;
    spec->height = s.height;
    spec->depth = s.depth;
    spec->nchannels = s.nchannels;
    spec->alphaChannel = s.alpha_channel;
    spec->isFloat = s.format.is_floating_point() ? 1 : 0;
    spec->isUint8 = s.format.basetype == OIIO::TypeDesc::UINT8 ? 1 : 0;
    spec->deep = s.deep ? 1 : 0;
}

int ReadFloat(PrismOiioInput *h, int nchannels, float *out, char *err, size_t errSize) {
    try {
        if (!h->in->read_image(0, 0, 0, nchannels, OIIO::TypeDesc::FLOAT, out)) {
            ReportError(h->in.get(), err, errSize);
            return 0;
        }
        return 1;
    } catch (const std::exception &e) {
        CopyError(e.what(), err, errSize);
        return 0;
    }
}

void Close(PrismOiioInput *h) {
    if (!h) return;
    if (h->in) h->in->close();
    delete h;
}

int Write(const char *name, int width, int height, int channels, int alphaChannel, int isFloat,
          const void *data, const char *colorSpace, const char *compression,
          int (*sink)(void *ctx, const unsigned char *bytes, size_t size), void *sinkCtx, char *err,
          size_t errSize) {
    try {
        OIIO::TypeDesc type = isFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
        OIIO::ImageSpec spec(width, height, channels, type);
        if (alphaChannel >= 0) spec.alpha_channel = alphaChannel;
        spec.attribute("oiio:UnassociatedAlpha", 1);  // do not let OIIO un-premultiply
        spec.attribute("oiio:ColorSpace", colorSpace);
        if (compression && *compression) spec.attribute("Compression", compression);
        auto out = OIIO::ImageOutput::create(name);
        if (!out) {
            ReportError(static_cast<OIIO::ImageOutput *>(nullptr), err, errSize);
            return 0;
        }
        // Into memory: the writers Prism uses (HDR, TGA, BMP, JPEG) all take an IOProxy, so
        // OpenImageIO never opens a file by name (Prism writes the bytes through its own
        // checked temporary file) and a full disk cannot fail inside a codec library.
        if (!out->supports("ioproxy")) {
            CopyError("OpenImageIO cannot encode this format in memory", err, errSize);
            return 0;
        }
        std::vector<unsigned char> bytes;
        OIIO::Filesystem::IOVecOutput proxy(bytes);
        if (!out->set_ioproxy(&proxy) || !out->open(name, spec)) {
            ReportError(out.get(), err, errSize);
            return 0;
        }
        if (!out->write_image(type, data)) {
            ReportError(out.get(), err, errSize);
            out->close();
            return 0;
        }
        if (!out->close()) {
            ReportError(out.get(), err, errSize);
            return 0;
        }
        return sink(sinkCtx, bytes.data(), bytes.size());
    } catch (const std::exception &e) {
        CopyError(e.what(), err, errSize);
        return 0;
    }
}

const PrismOiioModule kModule = {
    PRISM_OIIO_MODULE_VERSION, OpenFile, OpenMemory, GetSpec, ReadFloat, Close, Write};

}  // namespace

extern "C" __attribute__((visibility("default"))) const PrismOiioModule *PrismOiioModuleEntry() {
    return &kModule;
}
