// PLY reader: header parsing with located errors, size validation before allocation, and a
// single scalar-at-a-time data reader shared by the ascii and binary encodings.
#include "scene/ply_reader.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "core/file_io.h"
#include "core/memory.h"

namespace prism {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLE, BinaryBE };

int TypeSize(PlyType t) {
    switch (t) {
        case PlyType::Int8:
        case PlyType::UInt8:
            return 1;
        case PlyType::Int16:
        case PlyType::UInt16:
            return 2;
        case PlyType::Int32:
        case PlyType::UInt32:
        case PlyType::Float32:
            return 4;
        case PlyType::Float64:
            return 8;
    }
    return 1;
}

bool ParseType(const std::string &s, PlyType *t) {
    static const struct {
        const char *name;
        PlyType type;
    } table[] = {
        {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64}};
    for (const auto &e : table)
        if (s == e.name) {
            *t = e.type;
            return true;
        }
    return false;
}

// Vertex property slots we keep; everything else is read and dropped.
enum Slot { SlotX, SlotY, SlotZ, SlotNX, SlotNY, SlotNZ, SlotU, SlotV, SlotCount };

int VertexSlot(const std::string &n) {
    if (n == "x") return SlotX;
    if (n == "y") return SlotY;
    if (n == "z") return SlotZ;
    if (n == "nx") return SlotNX;
    if (n == "ny") return SlotNY;
    if (n == "nz") return SlotNZ;
    if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") return SlotU;
    if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") return SlotV;
    return -1;
}

struct PlyProperty {
    std::string name;
    bool isList = false;
    PlyType countType = PlyType::UInt8, valueType = PlyType::Float32;
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> props;
    FileLoc loc;
};

std::string Plural(const std::string &element) {
    if (element == "vertex") return "vertices";
    if (element == "face") return "faces";
    return "\"" + element + "\" elements";
}

struct Token {
    std::string text;
    int column;
};

std::vector<Token> SplitLine(const std::string &line) {
    std::vector<Token> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) out.push_back({line.substr(start, i - start), int(start) + 1});
    }
    return out;
}

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    size_t dataOffset = 0;
    int dataLine = 0;  // line number where ascii data starts
};

PlyHeader ParseHeader(const std::string &path, const std::string &buf) {
    PlyHeader h;
    size_t pos = 0;
    int lineNo = 0;
    bool haveFormat = false, done = false;
    while (!done) {
        if (pos >= buf.size()) throw SceneError(FileLoc{path}, "missing \"end_header\" line");
        size_t eol = buf.find('\n', pos);
        if (eol == std::string::npos) eol = buf.size();
        std::string line = buf.substr(pos, eol - pos);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        pos = eol + 1;
        ++lineNo;
        std::vector<Token> tok = SplitLine(line);
        FileLoc loc{path, lineNo, 1};
        auto At = [&](size_t i) {
            return FileLoc{path, lineNo, i < tok.size() ? tok[i].column : int(line.size()) + 1};
        };
        if (lineNo == 1) {
            if (tok.size() != 1 || tok[0].text != "ply") throw SceneError(loc, "not a PLY file");
            continue;
        }
        if (tok.empty()) continue;
        const std::string &kw = tok[0].text;
        if (kw == "comment" || kw == "obj_info") continue;
        if (kw == "format") {
            if (tok.size() < 2) throw SceneError(loc, "bad format line");
            const std::string &f = tok[1].text;
            if (f == "ascii")
                h.format = PlyFormat::Ascii;
            else if (f == "binary_little_endian")
                h.format = PlyFormat::BinaryLE;
            else if (f == "binary_big_endian")
                h.format = PlyFormat::BinaryBE;
            else
                throw SceneError(At(1), "bad format line: unknown format \"" + f + "\"");
            haveFormat = true;
        } else if (kw == "element") {
            if (tok.size() != 3) throw SceneError(loc, "bad element line");
            PlyElement e;
            e.name = tok[1].text;
            e.loc = loc;
            const std::string &c = tok[2].text;
            auto r = std::from_chars(c.data(), c.data() + c.size(), e.count);
            if (r.ec != std::errc() || r.ptr != c.data() + c.size())
                throw SceneError(At(2), "bad element count \"" + c + "\"");
            h.elements.push_back(std::move(e));
        } else if (kw == "property") {
            if (h.elements.empty()) throw SceneError(loc, "property before any element");
            PlyProperty p;
            if (tok.size() >= 2 && tok[1].text == "list") {
                if (tok.size() != 5) throw SceneError(loc, "bad list property line");
                if (!ParseType(tok[2].text, &p.countType))
                    throw SceneError(At(2), "unknown property type \"" + tok[2].text + "\"");
                if (!ParseType(tok[3].text, &p.valueType))
                    throw SceneError(At(3), "unknown property type \"" + tok[3].text + "\"");
                if (p.countType == PlyType::Float32 || p.countType == PlyType::Float64)
                    throw SceneError(At(2), "list count type must be an integer type");
                p.isList = true;
                p.name = tok[4].text;
            } else {
                if (tok.size() != 3) throw SceneError(loc, "bad property line");
                if (!ParseType(tok[1].text, &p.valueType))
                    throw SceneError(At(1), "unknown property type \"" + tok[1].text + "\"");
                p.name = tok[2].text;
            }
            h.elements.back().props.push_back(p);
        } else if (kw == "end_header") {
            done = true;
        } else {
            throw SceneError(At(0), "unknown header keyword \"" + kw + "\"");
        }
    }
    if (!haveFormat) throw SceneError(FileLoc{path}, "missing \"format\" line");
    h.dataOffset = std::min(pos, buf.size());
    h.dataLine = lineNo + 1;
    return h;
}

// Smallest number of bytes one element can occupy, so counts can be checked against the file
// size before allocating: binary lists need at least their count, ascii values at least one
// character plus a separator.
uint64_t MinElementBytes(const PlyElement &e, PlyFormat f) {
    uint64_t n = 0;
    for (const PlyProperty &p : e.props)
        n += f == PlyFormat::Ascii ? 2 : uint64_t(TypeSize(p.isList ? p.countType : p.valueType));
    return n;
}

// Reads scalars one at a time from the data section. Returns false at the end of the file;
// throws for malformed ascii numbers.
class DataReader {
  public:
    DataReader(const std::string &path, const std::string &buf, const PlyHeader &h)
        : path_(path),
          p_(buf.data() + h.dataOffset),
          end_(buf.data() + buf.size()),
          format_(h.format),
          line_(h.dataLine) {}

    bool Read(PlyType t, double *v) {
        if (format_ == PlyFormat::Ascii) return ReadAscii(v);
        int size = TypeSize(t);
        if (end_ - p_ < size) return false;
        unsigned char b[8];
        std::memcpy(b, p_, size_t(size));
        p_ += size;
        bool little = std::endian::native == std::endian::little;
        if ((format_ == PlyFormat::BinaryLE) != little)
            for (int i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
        switch (t) {
            case PlyType::Int8: {
                int8_t x;
                std::memcpy(&x, b, 1);
                *v = x;
                break;
            }
            case PlyType::UInt8: {
                *v = b[0];
                break;
            }
            case PlyType::Int16: {
                int16_t x;
                std::memcpy(&x, b, 2);
                *v = x;
                break;
            }
            case PlyType::UInt16: {
                uint16_t x;
                std::memcpy(&x, b, 2);
                *v = x;
                break;
            }
            case PlyType::Int32: {
                int32_t x;
                std::memcpy(&x, b, 4);
                *v = x;
                break;
            }
            case PlyType::UInt32: {
                uint32_t x;
                std::memcpy(&x, b, 4);
                *v = x;
                break;
            }
            case PlyType::Float32: {
                float x;
                std::memcpy(&x, b, 4);
                *v = x;
                break;
            }
            case PlyType::Float64: {
                double x;
                std::memcpy(&x, b, 8);
                *v = x;
                break;
            }
        }
        return true;
    }

    // Skips n values of type t; false if the file ends first.
    bool Skip(PlyType t, uint64_t n) {
        if (format_ != PlyFormat::Ascii) {
            uint64_t bytes = uint64_t(TypeSize(t));
            if (n > uint64_t(end_ - p_) / bytes) return false;
            p_ += n * bytes;
            return true;
        }
        double v;
        for (uint64_t i = 0; i < n; ++i)
            if (!ReadAscii(&v)) return false;
        return true;
    }

    FileLoc Loc() const {
        return format_ == PlyFormat::Ascii ? FileLoc{path_, line_, 0} : FileLoc{path_};
    }

  private:
    bool ReadAscii(double *v) {
        while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\n')) {
            if (*p_ == '\n') ++line_;
            ++p_;
        }
        if (p_ == end_) return false;
        const char *start = p_;
        while (p_ < end_ && *p_ != ' ' && *p_ != '\t' && *p_ != '\r' && *p_ != '\n') ++p_;
        const char *s = start;
        if (s < p_ && *s == '+') ++s;  // from_chars rejects a leading '+'
        auto r = std::from_chars(s, p_, *v);
        if (r.ec != std::errc() || r.ptr != p_)
            throw SceneError(FileLoc{path_, line_, 0},
                             "bad number \"" + std::string(start, p_) + "\" in data");
        return true;
    }

    std::string path_;
    const char *p_, *end_;
    PlyFormat format_;
    int line_;
};

// A list count read from the file (as a double, like every value): a non-negative integer
// small enough to convert. An ascii file can say 1e62, which does not fit any integer type.
bool ListCount(double n, uint64_t *count) {
    if (!(n >= 0 && n <= 9007199254740992.0) || n != std::floor(n)) return false;
    *count = uint64_t(n);
    return true;
}

struct FaceStats {
    uint64_t fanned = 0, degenerate = 0;
};

void ReadVertices(const PlyElement &e, DataReader &r, PlyMesh &mesh) {
    std::vector<int> slots;
    bool have[SlotCount] = {};
    for (const PlyProperty &p : e.props) {
        int s = p.isList ? -1 : VertexSlot(p.name);
        slots.push_back(s);
        if (s >= 0) have[s] = true;
    }
    if (!have[SlotX] || !have[SlotY] || !have[SlotZ])
        throw SceneError(e.loc, "vertex element lacks x, y and z properties");
    bool hasN = have[SlotNX] && have[SlotNY] && have[SlotNZ];
    bool hasUV = have[SlotU] && have[SlotV];
    mesh.P.resize(size_t(e.count));
    if (hasN) mesh.N.resize(size_t(e.count));
    if (hasUV) mesh.uv.resize(size_t(e.count));
    for (uint64_t i = 0; i < e.count; ++i) {
        double val[SlotCount] = {};
        for (size_t k = 0; k < e.props.size(); ++k) {
            const PlyProperty &p = e.props[k];
            bool ok;
            if (p.isList) {
                double n;
                uint64_t c;
                ok = r.Read(p.countType, &n) && ListCount(n, &c) && r.Skip(p.valueType, c);
            } else {
                double v;
                ok = r.Read(p.valueType, &v);
                if (ok && slots[k] >= 0) val[slots[k]] = v;
            }
            if (!ok)
                throw SceneError(FileLoc{r.Loc().file}, "file ends after " + std::to_string(i) +
                                                            " of " + std::to_string(e.count) +
                                                            " vertices");
        }
        mesh.P[i] = Vec3f(float(val[SlotX]), float(val[SlotY]), float(val[SlotZ]));
        if (hasN) mesh.N[i] = Vec3f(float(val[SlotNX]), float(val[SlotNY]), float(val[SlotNZ]));
        if (hasUV) mesh.uv[i] = Vec2f(float(val[SlotU]), float(val[SlotV]));
    }
}

void ReadFaces(const PlyElement &e, DataReader &r, uint64_t nVertices, PlyMesh &mesh,
               FaceStats &stats) {
    int listProp = -1;
    for (size_t k = 0; k < e.props.size(); ++k)
        if (e.props[k].isList &&
            (e.props[k].name == "vertex_indices" || e.props[k].name == "vertex_index"))
            listProp = int(k);
    if (listProp < 0)
        throw SceneError(e.loc, "face element lacks a \"vertex_indices\" list property");
    mesh.indices.reserve(size_t(e.count) * 3);
    std::vector<int> face;
    auto Truncated = [&](uint64_t i) {
        return SceneError(FileLoc{r.Loc().file}, "file ends after " + std::to_string(i) + " of " +
                                                     std::to_string(e.count) + " faces");
    };
    for (uint64_t i = 0; i < e.count; ++i) {
        face.clear();
        for (size_t k = 0; k < e.props.size(); ++k) {
            const PlyProperty &p = e.props[k];
            double n;
            if (!p.isList) {
                if (!r.Read(p.valueType, &n)) throw Truncated(i);
                continue;
            }
            if (!r.Read(p.countType, &n)) throw Truncated(i);
            uint64_t count;
            if (!ListCount(n, &count))
                throw SceneError(r.Loc(), "face " + std::to_string(i) + " has a bad vertex count");
            if (int(k) != listProp) {
                if (!r.Skip(p.valueType, count)) throw Truncated(i);
                continue;
            }
            for (uint64_t j = 0; j < count; ++j) {
                double idx;
                if (!r.Read(p.valueType, &idx)) throw Truncated(i);
                if (!(idx >= 0 && idx < double(nVertices)) || idx != std::floor(idx)) {
                    char num[32];
                    std::snprintf(num, sizeof(num), "%.17g", idx);
                    throw SceneError(r.Loc(), "face " + std::to_string(i) + " references vertex " +
                                                  num + ", but there are " +
                                                  std::to_string(nVertices) + " vertices");
                }
                face.push_back(int(idx));
            }
        }
        if (face.size() < 3) {
            ++stats.degenerate;
            continue;
        }
        if (face.size() > 4) ++stats.fanned;
        if (face.size() == 4) mesh.quadFirst.push_back(uint32_t(mesh.indices.size() / 3));
        for (size_t j = 1; j + 1 < face.size(); ++j) {
            mesh.indices.push_back(face[0]);
            mesh.indices.push_back(face[j]);
            mesh.indices.push_back(face[j + 1]);
        }
    }
}

void SkipElement(const PlyElement &e, DataReader &r) {
    if (e.props.empty()) return;
    for (uint64_t i = 0; i < e.count; ++i)
        for (const PlyProperty &p : e.props) {
            double n = 0;
            uint64_t c;
            bool ok = p.isList
                          ? r.Read(p.countType, &n) && ListCount(n, &c) && r.Skip(p.valueType, c)
                          : r.Read(p.valueType, &n);
            if (!ok)
                throw SceneError(FileLoc{r.Loc().file}, "file ends after " + std::to_string(i) +
                                                            " of " + std::to_string(e.count) + " " +
                                                            Plural(e.name));
        }
}

}  // namespace

uint64_t PlyMeshBytes(uint64_t fileBytes, uint64_t vertices, uint64_t faces) {
    return fileBytes + vertices * 32 + faces * 24;
}

PlyMesh ReadPlyFile(const std::string &path, Diagnostics &diag, uint64_t maxBytes) {
    MemoryBudget budget(maxBytes);
    return ReadPlyFile(path, diag, budget);
}

PlyMesh ReadPlyFile(const std::string &path, Diagnostics &diag, MemoryBudget &budget) {
    // The file is a transient buffer, counted with the mesh below.
    std::string buf;
    {
        FileReadError error;
        if (!ReadFileContents(path, &buf, &error, budget.Remaining())) {
            if (!error.tooLarge)
                throw SceneError(FileLoc{path},
                                 "cannot open file " + Quote(path) + ": " + error.reason);
            budget.Check(error.size, "file", FileLoc{path});
            buf = ReadFileOrThrow(path, FileLoc{path});  // memory was released meanwhile
        }
    }
    PlyHeader h = ParseHeader(path, buf);

    // Check every element count against the bytes that remain before allocating anything.
    const PlyElement *vertexElem = nullptr;
    uint64_t remaining = buf.size() - h.dataOffset;
    // An ascii file's last value needs no trailing separator.
    if (h.format == PlyFormat::Ascii) remaining += 1;
    // While every element so far has a fixed binary size, the shortfall is known exactly.
    bool exact = h.format != PlyFormat::Ascii;
    for (const PlyElement &e : h.elements) {
        uint64_t minBytes = MinElementBytes(e, h.format);
        for (const PlyProperty &p : e.props) exact &= !p.isList;
        if (minBytes > 0 && e.count > remaining / minBytes) {
            if (exact)
                throw SceneError(e.loc, "file ends after " + std::to_string(remaining / minBytes) +
                                            " of " + std::to_string(e.count) + " " +
                                            Plural(e.name));
            throw SceneError(e.loc, "header claims " + std::to_string(e.count) + " " +
                                        Plural(e.name) + ", more than the file size allows");
        }
        remaining -= e.count * minBytes;
        if (e.name == "vertex") {
            if (vertexElem) throw SceneError(e.loc, "more than one vertex element");
            vertexElem = &e;
        }
    }
    if (!vertexElem) throw SceneError(FileLoc{path}, "no vertex element");
    if (vertexElem->count > uint64_t(std::numeric_limits<int>::max()))
        throw SceneError(vertexElem->loc, "too many vertices");
    // Memory budget: counts are bounded by the file size, so PlyMeshBytes cannot overflow.
    {
        uint64_t faces = 0;
        for (const PlyElement &e : h.elements)
            if (e.name == "face") faces += e.count;
        budget.Charge(PlyMeshBytes(buf.size(), vertexElem->count, faces), "mesh", vertexElem->loc);
    }

    PlyMesh mesh;
    DataReader reader(path, buf, h);
    FaceStats stats;
    bool haveFaces = false;
    for (const PlyElement &e : h.elements) {
        if (e.name == "vertex") {
            ReadVertices(e, reader, mesh);
        } else if (e.name == "face" && !haveFaces) {
            ReadFaces(e, reader, vertexElem->count, mesh, stats);
            haveFaces = true;
        } else {
            if (e.name == "tristrips" && e.count > 0)
                diag.Warn(e.loc, "triangle strips are not supported; element ignored");
            SkipElement(e, reader);
        }
    }
    if (stats.degenerate > 0)
        diag.Warn(FileLoc{path}, std::to_string(stats.degenerate) +
                                     " faces with fewer than 3 vertices were skipped");
    if (stats.fanned > 0)
        diag.Warn(FileLoc{path}, std::to_string(stats.fanned) +
                                     " faces with more than 4 vertices were fanned into triangles");
    if (!haveFaces) diag.Warn(FileLoc{path}, "no face element: the mesh has no triangles");
    return mesh;
}

}  // namespace prism
