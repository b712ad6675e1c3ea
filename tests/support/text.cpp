#include "support/text.h"

#include <cstdint>

namespace prism::test {

std::string Base64(const std::string &bin) {
    static const char *const k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bin.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bin[i])) << 16;
        if (i + 1 < bin.size()) v |= uint32_t(uint8_t(bin[i + 1])) << 8;
        if (i + 2 < bin.size()) v |= uint32_t(uint8_t(bin[i + 2]));
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < bin.size() ? k[(v >> 6) & 63] : '=';
        out += i + 2 < bin.size() ? k[v & 63] : '=';
    }
    return out;
}

std::string AsciiPly(int nv) {
    std::string s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(nv) +
                    "\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < nv; ++i) s += "0 0 " + std::to_string(i) + "\n";
    return s + "3 0 1 2\n";
}

const char *const kCliHead =
    "LookAt 0 0 5  0 0 0  0 1 0\n"
    "Camera \"perspective\" \"float fov\" 40\n"
    "Film \"image\" \"integer xresolution\" 8 \"integer yresolution\" 8\n"
    "WorldBegin\n"
    "LightSource \"point\" \"rgb I\" [10 10 10] \"point from\" [0 0 5]\n";

const char *const kLitFloorFromLookAt =
    "LookAt 0 1 -4  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [50]\n"
    "WorldBegin\n"
    "LightSource \"point\" \"point from\" [1.5 2 -1] \"rgb I\" [2 2 2]\n"
    "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 4 4]\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-0.5 2.5 -0.5  0.5 2.5 -0.5  0.5 2.5 0.5  -0.5 2.5 0.5]\n"
    "AttributeEnd\n"
    "Material \"matte\" \"rgb Kd\" [0.6 0.5 0.4]\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-3 0 -3  3 0 -3  3 0 3  -3 0 3]\n";

std::string ReplaceFirst(std::string s, const std::string &from, const std::string &to) {
    const size_t p = s.find(from);
    if (p != std::string::npos) s.replace(p, from.size(), to);
    return s;
}

const char *const kClosedRoom =
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3  4 5 6 4 6 7  8 9 10 8 10 11"
    "  12 13 14 12 14 15  16 17 18 16 18 19  20 21 22 20 22 23]\n"
    "  \"point P\" [-2 0 -2 2 0 -2 2 0 2 -2 0 2   -2 0 -2 2 0 -2 2 4 -2 -2 4 -2"
    "   -2 0 2 2 0 2 2 4 2 -2 4 2   2 0 -2 2 0 2 2 4 2 2 4 -2   -2 0 -2 -2 0 2 -2 4 2"
    " -2 4 -2  -2 4 -2 2 4 -2 2 4 2 -2 4 2]\n";

}  // namespace prism::test
