// dlopen() of libprism_oiio.so at first use; see oiio_loader.h.
#include "image/oiio_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef PRISM_OIIO_MODULE_NAME
#define PRISM_OIIO_MODULE_NAME "libprism_oiio.so"
#endif

namespace prism {

namespace {

namespace fs = std::filesystem;

std::atomic<bool> loaded{false};

std::vector<std::string> Candidates() {
    if (const char *env = std::getenv("PRISM_OIIO_MODULE"); env && *env) return {env};
    std::vector<std::string> paths;
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) paths.push_back((exe.parent_path() / PRISM_OIIO_MODULE_NAME).string());
#ifdef PRISM_OIIO_MODULE_BUILD_PATH
    paths.push_back(PRISM_OIIO_MODULE_BUILD_PATH);
#endif
    return paths;
}

const PrismOiioModule *Load(std::string *error) {
    std::string tried;
    auto note = [&](const std::string &path, const std::string &why) {
        tried += (tried.empty() ? " " : "; ") + path + ": " + why;
    };
    for (const std::string &path : Candidates()) {
        std::error_code ec;
        if (!fs::exists(path, ec)) {
            note(path, "not found");
            continue;
        }
        // RTLD_LOCAL keeps OpenImageIO's symbols out of the global namespace. The handle is
        // never closed: OIIO's plugins and thread pools live until exit.
        void *handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char *why = dlerror();
            note(path, why ? why : "dlopen failed");
            continue;
        }
        auto entry =
            reinterpret_cast<PrismOiioModuleEntryFn>(dlsym(handle, PRISM_OIIO_MODULE_ENTRY));
        const PrismOiioModule *module = entry ? entry() : nullptr;
        if (!module || module->version != PRISM_OIIO_MODULE_VERSION) {
            note(path, "not a compatible Prism OpenImageIO module");
            continue;
        }
        return module;
    }
    *error = "the OpenImageIO module " PRISM_OIIO_MODULE_NAME " could not be loaded; tried" + tried;
    return nullptr;
}

}  // namespace

const PrismOiioModule &OiioModule() {
    static std::string error;
    static const PrismOiioModule *module = [] {
        const PrismOiioModule *m = Load(&error);
        loaded = m != nullptr;
        return m;
    }();
    if (!module) throw std::runtime_error(error);
    return *module;
}

bool OiioModuleLoaded() { return loaded; }

}  // namespace prism
