#include "scene/scene_description.h"

#include <filesystem>

#include "core/file_io.h"

namespace prism {

uint64_t ShapeDescBytes(const ShapeDesc &s) {
    return sizeof(ShapeDesc) + s.type.size() + s.loc.file.size() + s.name.size() +
           s.mediumLoc.file.size() + ParamStorageBytes(s.params);
}

const ObjectDesc *FindObject(const SceneDescription &desc, const std::string &name) {
    for (auto it = desc.objects.rbegin(); it != desc.objects.rend(); ++it)
        if (it->name == name) return &*it;
    return nullptr;
}

std::string ResolveScenePath(const std::string &baseDir, const std::string &file) {
    std::filesystem::path p(file);
    if (p.is_absolute() || baseDir.empty()) return file;
    return (std::filesystem::path(baseDir) / p).string();
}

bool IsInsideDirectory(const std::string &canonicalPath, const std::string &dir) {
    std::filesystem::path base = CanonicalPath(dir.empty() ? "." : dir);
    std::filesystem::path rel = std::filesystem::path(canonicalPath).lexically_relative(base);
    return !rel.empty() && *rel.begin() != "..";
}

}  // namespace prism
