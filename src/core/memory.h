// The memory budget (`--max-memory`): its default, parsing of sizes such as "512M" or "8G",
// and formatting for messages. Readers and the renderer check large allocations against it.
#pragma once

#include <cstdint>
#include <string>

namespace prism {

// Physical RAM in bytes (0 if unknown).
uint64_t PhysicalMemoryBytes();
// 75% of physical RAM (4 GiB if that is unknown).
uint64_t DefaultMemoryBudget();
// `budget` itself, or DefaultMemoryBudget() when it is 0 ("not set").
inline uint64_t EffectiveMemoryBudget(uint64_t budget) {
    return budget ? budget : DefaultMemoryBudget();
}
// "1048576", "512K", "512M", "1.5G", "2T" (binary units; an optional trailing "B" or "iB").
// Returns false for anything else, including 0 and sizes beyond 2^63.
bool ParseMemorySize(const std::string &s, uint64_t *bytes);
// "512 MiB", "1.5 GiB", "100 bytes".
std::string FormatBytes(uint64_t bytes);

}  // namespace prism
