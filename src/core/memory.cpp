#include "core/memory.h"

#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace prism {

uint64_t PhysicalMemoryBytes() {
    long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return 0;
    return uint64_t(pages) * uint64_t(pageSize);
}

uint64_t DefaultMemoryBudget() {
    uint64_t ram = PhysicalMemoryBytes();
    return ram ? ram / 4 * 3 : uint64_t(4) << 30;
}

bool ParseMemorySize(const std::string &s, uint64_t *bytes) {
    const char *begin = s.c_str();
    if (s.empty() || !(std::isdigit((unsigned char)s[0]) || s[0] == '.')) return false;
    char *end = nullptr;
    double v = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(v) || !(v > 0)) return false;
    std::string unit(end);
    for (char &c : unit) c = char(std::toupper((unsigned char)c));
    if (unit.size() >= 3 && unit.substr(unit.size() - 2) == "IB") unit.resize(unit.size() - 2);
    else if (unit.size() >= 2 && unit.back() == 'B') unit.pop_back();
    double scale = 1;
    if (unit == "" || unit == "B") scale = 1;
    else if (unit == "K") scale = 1024.0;
    else if (unit == "M") scale = 1024.0 * 1024;
    else if (unit == "G") scale = 1024.0 * 1024 * 1024;
    else if (unit == "T") scale = 1024.0 * 1024 * 1024 * 1024;
    else return false;
    double b = std::floor(v * scale);
    if (!(b >= 1) || b >= 9.2e18) return false;
    *bytes = uint64_t(b);
    return true;
}

std::string FormatBytes(uint64_t bytes) {
    const char *units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    if (bytes < 1024) return std::to_string(bytes) + " bytes";
    double v = double(bytes) / 1024;
    int u = 0;
    while (v >= 1024 && u < 5) {
        v /= 1024;
        ++u;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, v < 10 ? "%.1f %s" : "%.0f %s", v, units[u]);
    return buf;
}

}  // namespace prism
