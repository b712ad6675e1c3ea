// STL reader: binary by its exact size, ASCII by a located tokenizer; both feed one welder.
#include "scene/stl_reader.h"

#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "core/file_io.h"
#include "core/memory.h"
#include "scene/param_builders.h"

namespace prism {

using namespace reader;

namespace {

constexpr uint64_t kHeaderBytes = 84, kFacetBytes = 50;

// STL's numbers are little-endian.
uint32_t LittleU32(const char *p) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
    return v;
}

// Positions welded where their float bits are equal (-0 counts as +0), in first-seen order.
// The buffers are checked against the budget as they grow (an ASCII polygon of n vertices is
// n - 2 triangles, so the text's size does not bound them).
class Welder {
  public:
    Welder(uint64_t triangles, MemoryBudget &budget, FileLoc loc)
        : budget_(budget), loc_(std::move(loc)) {
        budget_.Check(StlWeldBytes(triangles), "STL welding buffers", loc_);
        P_.reserve(size_t(triangles));  // about half a vertex a triangle in a closed mesh
        indices_.reserve(size_t(triangles) * 3);
        index_.reserve(size_t(triangles));
    }
    void Add(Vec3f p) {
        if (indices_.size() >= nextCheck_) {  // at 1024, 2048, 4096, ... triangles
            budget_.Check(StlWeldBytes(2 * indices_.size() / 3), "STL welding buffers", loc_);
            nextCheck_ = 2 * indices_.size();
        }
        p = Vec3f(p.x + 0.f, p.y + 0.f, p.z + 0.f);  // -0 + 0 is +0
        const Key k{std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y),
                    std::bit_cast<uint32_t>(p.z)};
        auto [it, added] = index_.try_emplace(k, int(P_.size()));
        if (added) P_.push_back(p);
        indices_.push_back(it->second);
    }
    size_t Triangles() const { return indices_.size() / 3; }
    // The mesh so far as a shape, and a fresh start for the next solid.
    ShapeDesc Take(const std::string &name, const FileLoc &loc) {
        ShapeDesc s;
        s.type = "trianglemesh";
        s.loc = loc;
        s.name = name;
        s.params = TriangleMeshParams(indices_, P_, {}, {}, loc);
        P_.clear();
        indices_.clear();
        index_.clear();
        nextCheck_ = 3 * 1024;
        return s;
    }

  private:
    using Key = std::array<uint32_t, 3>;
    struct KeyHash {
        size_t operator()(const Key &k) const {
            uint64_t h = k[0] * 0x9E3779B97F4A7C15ull;
            h ^= (h >> 29) + k[1] * 0xBF58476D1CE4E5B9ull;
            h ^= (h >> 31) + k[2] * 0x94D049BB133111EBull;
            return size_t(h ^ (h >> 32));
        }
    };
    MemoryBudget &budget_;
    FileLoc loc_;
    std::vector<Vec3f> P_;
    std::vector<int> indices_;
    size_t nextCheck_ = 3 * 1024;
    std::unordered_map<Key, int, KeyHash> index_;
};

void AddShape(SceneDescription &desc, Welder &w, const std::string &name, const FileLoc &loc,
              MemoryBudget &budget) {
    if (w.Triangles() == 0) return;
    ShapeDesc s = w.Take(name, loc);
    budget.Charge(ParamStorageBytes(s.params), "mesh", loc);
    s.directiveIndex = int(desc.shapes.size());
    desc.shapes.push_back(std::move(s));
}

std::string Describe(float v) { return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"; }

void ReadBinary(const std::string &path, const std::string &data, SceneDescription &desc,
                MemoryBudget &budget) {
    const uint32_t count = LittleU32(data.data() + 80);
    const FileLoc loc{path};
    Welder w(count, budget, loc);
    for (uint32_t t = 0; t < count; ++t) {
        const char *facet = data.data() + kHeaderBytes + uint64_t(t) * kFacetBytes;
        for (int v = 0; v < 3; ++v) {
            float c[3];
            for (int i = 0; i < 3; ++i) {  // after the facet normal
                const float x = std::bit_cast<float>(LittleU32(facet + 12 + 12 * v + 4 * i));
                c[i] = x;
                if (!std::isfinite(x))
                    throw SceneError(loc,
                                     "triangle " + std::to_string(t) + " (byte " +
                                         std::to_string(facet + 12 + 12 * v + 4 * i - data.data()) +
                                         "): a vertex coordinate is " + Describe(x));
            }
            w.Add(Vec3f(c[0], c[1], c[2]));
        }
    }
    AddShape(desc, w, std::filesystem::path(path).stem().string(), loc, budget);
}

// Whitespace-separated words with their line and column.
class Words {
  public:
    Words(const std::string &path, const std::string &text) : path_(path), text_(text) {}
    bool Next(std::string_view *word, FileLoc *loc) {
        while (pos_ < text_.size() && IsSpace(text_[pos_])) Advance();
        if (pos_ >= text_.size()) return false;
        *loc = Here();
        const size_t start = pos_;
        while (pos_ < text_.size() && !IsSpace(text_[pos_])) Advance();
        *word = std::string_view(text_).substr(start, pos_ - start);
        return true;
    }
    // The rest of the current line (a solid's name), trimmed.
    std::string RestOfLine() {
        while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) Advance();
        const size_t start = pos_;
        while (pos_ < text_.size() && text_[pos_] != '\n') Advance();
        std::string s = text_.substr(start, pos_ - start);
        while (!s.empty() && IsSpace(s.back())) s.pop_back();
        return s;
    }
    FileLoc Here() const { return FileLoc{path_, line_, int(pos_ - lineStart_) + 1}; }

  private:
    static bool IsSpace(char c) {
        return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
    }
    void Advance() {
        if (text_[pos_++] == '\n') ++line_, lineStart_ = pos_;
    }
    const std::string &path_;
    const std::string &text_;
    size_t pos_ = 0, lineStart_ = 0;
    int line_ = 1;
};

std::string Printable(std::string_view w) {
    std::string s(w.substr(0, 40));
    for (char &c : s)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    return "\"" + s + (w.size() > 40 ? "...\"" : "\"");
}

void ReadAscii(const std::string &path, const std::string &text, SceneDescription &desc,
               MemoryBudget &budget) {
    Words words(path, text);
    std::string_view w;
    FileLoc loc;
    auto next = [&](const char *what) {
        if (!words.Next(&w, &loc))
            throw SceneError(words.Here(), std::string("unexpected end of file: expected ") + what);
    };
    auto expect = [&](const char *keyword) {
        next(("\"" + std::string(keyword) + "\"").c_str());
        if (w != keyword)
            throw SceneError(loc,
                             "expected \"" + std::string(keyword) + "\", found " + Printable(w));
    };
    auto number = [&]() {
        next("a number");
        double v = 0;
        const char *end = w.data() + w.size();
        auto r = std::from_chars(w.data(), end, v);
        if (r.ec == std::errc::result_out_of_range)
            throw SceneError(loc, Printable(w) + " is out of range");
        if (r.ec != std::errc() || r.ptr != end)
            throw SceneError(loc, "expected a number, found " + Printable(w));
        const float f = float(v);
        if (!std::isfinite(f))
            throw SceneError(loc,
                             "a vertex coordinate is " + Describe(f) + " (" + Printable(w) + ")");
        return f;
    };
    Welder weld(0, budget, FileLoc{path});
    if (!words.Next(&w, &loc)) throw SceneError(FileLoc{path}, "empty STL file");
    while (true) {
        if (w != "solid") throw SceneError(loc, "expected \"solid\", found " + Printable(w));
        const FileLoc solidLoc = loc;
        std::string name = words.RestOfLine();
        if (name.empty()) name = std::filesystem::path(path).stem().string();
        while (true) {
            next("\"facet\" or \"endsolid\"");
            if (w == "endsolid") {
                words.RestOfLine();
                break;
            }
            if (w != "facet")
                throw SceneError(loc, "expected \"facet\" or \"endsolid\", found " + Printable(w));
            expect("normal");
            for (int i = 0; i < 3; ++i) number();  // not used: see stl_reader.h
            expect("outer");
            expect("loop");
            // Three vertices; a polygon of more is fanned, as some exporters write quads.
            std::vector<Vec3f> loop;
            while (true) {
                next("\"vertex\" or \"endloop\"");
                if (w == "endloop") break;
                if (w != "vertex")
                    throw SceneError(loc,
                                     "expected \"vertex\" or \"endloop\", found " + Printable(w));
                const float x = number(), y = number(), z = number();
                loop.emplace_back(x, y, z);
            }
            if (loop.size() < 3)
                throw SceneError(
                    loc, "a facet needs at least 3 vertices, found " + std::to_string(loop.size()));
            for (size_t i = 1; i + 1 < loop.size(); ++i) {
                weld.Add(loop[0]);
                weld.Add(loop[i]);
                weld.Add(loop[i + 1]);
            }
            expect("endfacet");
        }
        AddShape(desc, weld, name, solidLoc, budget);
        if (!words.Next(&w, &loc)) break;
    }
}

}  // namespace

uint64_t StlWeldBytes(uint64_t triangles) {
    // Positions (one a triangle reserved, up to three), indices and the hash table's nodes and
    // buckets (about 40 bytes a vertex).
    return triangles * (3 * sizeof(Vec3f) + 3 * sizeof(int) + 3 * 40);
}

SceneDescription ReadStlFile(const std::string &path, Diagnostics &diag, MemoryBudget *budget) {
    (void)diag;
    MemoryBudget own(0);
    MemoryBudget &b = budget ? *budget : own;
    const FileLoc fileLoc{path};
    const std::string data = ReadFileOrThrow(path, fileLoc, b, "scene file");
    SceneDescription desc;
    desc.format = "stl";
    // STL names no integrator: Prism's distribution integrator, as for OBJ, glTF and PLY.
    desc.integrator.type = "distribution";
    desc.sourceFile = path;
    desc.baseDir = DirectoryOf(path);
    bool binary = false;
    if (data.size() >= kHeaderBytes)
        binary = data.size() == kHeaderBytes + uint64_t(LittleU32(data.data() + 80)) * kFacetBytes;
    size_t first = 0;
    while (first < data.size() && std::isspace(static_cast<unsigned char>(data[first]))) ++first;
    // A binary file may begin with "solid" too; its count and floats hold zero bytes.
    const bool ascii = data.compare(first, 5, "solid") == 0 && data.find('\0') == std::string::npos;
    if (binary) {
        ReadBinary(path, data, desc, b);
    } else if (ascii) {
        ReadAscii(path, data, desc, b);
    } else if (data.size() >= kHeaderBytes) {
        const uint32_t count = LittleU32(data.data() + 80);
        throw SceneError(fileLoc, "binary STL claims " + std::to_string(count) +
                                      " triangles, which need " +
                                      std::to_string(kHeaderBytes + uint64_t(count) * kFacetBytes) +
                                      " bytes; the file has " + std::to_string(data.size()));
    } else {
        throw SceneError(fileLoc, "not an STL file: " + std::to_string(data.size()) +
                                      " bytes, neither ASCII (\"solid\") nor binary (84 or more)");
    }
    return desc;
}

}  // namespace prism
