// The readers under fuzzing. Readers that only take a path get the input through a file in a
// private per-process directory; the pbrt parser reads from memory and its includes are
// confined to that directory (which holds the input itself, so self-inclusion is reachable).
#include "fuzz_entry.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "image/image_io.h"
#include "render/fourier_bsdf.h"
#include "scene/gltf_reader.h"
#include "scene/obj_reader.h"
#include "scene/pbrt_parser.h"
#include "scene/ply_reader.h"
#include "scene/stl_reader.h"

namespace fs = std::filesystem;

namespace prism::fuzz {

namespace {

// Created on first use, removed at exit.
struct ScratchDir {
    fs::path path;
    ScratchDir() {
        path = fs::temp_directory_path() / ("prism-fuzz-" + std::to_string(getpid()));
        fs::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

const fs::path &Scratch() {
    static ScratchDir dir;
    return dir.path;
}

std::string WriteInput(const std::string &name, const uint8_t *data, size_t size) {
    fs::path p = Scratch() / name;
    FILE *f = std::fopen(p.c_str(), "wb");
    if (!f) throw std::logic_error("fuzz: cannot write " + p.string());
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
    return p.string();
}

}  // namespace

void FuzzPbrt(const uint8_t *data, size_t size, std::string *rejected) {
    std::string text(reinterpret_cast<const char *>(data), size);
    // The input is also on disk under its own name, so `Include "main.pbrt"` exercises the
    // cycle check and `Include "other.pbrt"` a missing file.
    std::string path = WriteInput("main.pbrt", data, size);
    PbrtParseOptions opts;
    opts.confineIncludes = true;
    opts.maxIncludeDepth = 8;
    Diagnostics diag;
    try {
        ParsePbrtString(text, path, diag, opts);
    } catch (const SceneError &e) {
        if (rejected) *rejected = e.what();
    }
}

void FuzzPly(const uint8_t *data, size_t size, std::string *rejected) {
    std::string path = WriteInput("mesh.ply", data, size);
    Diagnostics diag;
    try {
        ReadPlyFile(path, diag);
    } catch (const SceneError &e) {
        if (rejected) *rejected = e.what();
    }
}

void FuzzStl(const uint8_t *data, size_t size, std::string *rejected) {
    std::string path = WriteInput("mesh.stl", data, size);
    Diagnostics diag;
    try {
        ReadStlFile(path, diag);
    } catch (const SceneError &e) {
        if (rejected) *rejected = e.what();
    }
}

void FuzzObj(const uint8_t *data, size_t size, std::string *rejected) {
    // Everything after a line "#%MTL" is the material library "m.mtl"; seeds say "mtllib m.mtl".
    std::string text(reinterpret_cast<const char *>(data), size);
    std::string obj = text, mtl;
    size_t cut = text.find("#%MTL\n");
    if (cut != std::string::npos) {
        obj = text.substr(0, cut);
        mtl = text.substr(cut + 6);
    }
    WriteInput("m.mtl", reinterpret_cast<const uint8_t *>(mtl.data()), mtl.size());
    std::string path =
        WriteInput("scene.obj", reinterpret_cast<const uint8_t *>(obj.data()), obj.size());
    Diagnostics diag;
    try {
        ReadObjFile(path, diag);
    } catch (const SceneError &e) {
        if (rejected) *rejected = e.what();
    }
}

void FuzzGltf(const uint8_t *data, size_t size, std::string *rejected) {
    bool glb = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
    std::string path = WriteInput(glb ? "scene.glb" : "scene.gltf", data, size);
    Diagnostics diag;
    try {
        ReadGltfFile(path, diag);
    } catch (const SceneError &e) {
        if (rejected) *rejected = e.what();
    }
}

void FuzzImage(const uint8_t *data, size_t size, std::string *rejected) {
    // The name's extension picks OpenImageIO's reader; choose it from the magic bytes so the
    // fuzzer reaches each decoder, and fall back to TGA, which has no magic.
    auto starts = [&](const char *m) {
        size_t n = std::char_traits<char>::length(m);
        return size >= n && std::equal(m, m + n, reinterpret_cast<const char *>(data));
    };
    const char *ext = ".tga";
    if (starts("\x89PNG"))
        ext = ".png";
    else if (starts("\xff\xd8"))
        ext = ".jpg";
    else if (starts("v/1\x01"))
        ext = ".exr";
    else if (starts("#?"))
        ext = ".hdr";
    else if (starts("PF") || starts("Pf"))
        ext = ".pfm";
    else if (starts("BM"))
        ext = ".bmp";
    std::vector<unsigned char> bytes(data, data + size);
    ReadImageOptions opts;
    opts.maxPixels = int64_t(1) << 20;  // keeps each run fast; the check itself is under test
    opts.quietDecoders = false;         // sanitizer reports must reach stderr
    // Only the reader the extension names: OpenImageIO otherwise retries every format plugin
    // on a malformed file, which slows every run without reaching more of Prism's code.
    opts.tryAllFormats = false;
    try {
        ReadImageFromMemory(bytes, std::string("texture") + ext, opts);
    } catch (const std::runtime_error &e) {
        if (rejected) *rejected = e.what();
    }
}

void FuzzBsdf(const uint8_t *data, size_t size, std::string *rejected) {
    try {
        const FourierTable t =
            FourierTable::Parse(std::string(reinterpret_cast<const char *>(data), size), "fuzz");
        // Every lookup an accepted table allows: grid points, between them, both sides.
        const FourierLobe l{&t};
        for (float zo : {-0.95f, -0.3f, 0.f, 0.4f, 1.f}) {
            const Vec3f wo = Normalize(Vec3f(0.3f, 0.2f, zo == 0 ? 1e-3f : zo));
            for (float zi : {-1.f, -0.5f, 0.2f, 0.9f}) {
                const Vec3f wi = Normalize(Vec3f(-0.4f, 0.1f, zi));
                l.f(wo, wi);
                l.Pdf(wo, wi);
            }
            Vec3f wi;
            float pdf;
            for (float u : {0.f, 0.3f, 0.999f}) l.Sample(wo, {u, 1 - u}, &wi, &pdf);
            l.AlbedoEstimate(wo);
        }
    } catch (const std::runtime_error &e) {
        if (rejected) *rejected = e.what();
    }
}

bool FuzzByName(const std::string &target, const uint8_t *data, size_t size,
                std::string *rejected) {
    if (target == "pbrt")
        FuzzPbrt(data, size, rejected);
    else if (target == "ply")
        FuzzPly(data, size, rejected);
    else if (target == "stl")
        FuzzStl(data, size, rejected);
    else if (target == "obj")
        FuzzObj(data, size, rejected);
    else if (target == "gltf")
        FuzzGltf(data, size, rejected);
    else if (target == "image")
        FuzzImage(data, size, rejected);
    else if (target == "bsdf")
        FuzzBsdf(data, size, rejected);
    else if (target == "gltf_json")
        FuzzGltfJson(data, size, rejected);
    else if (target == "texture")
        FuzzTextureGraph(data, size, rejected);
    else
        return false;
    return true;
}

}  // namespace prism::fuzz
