// Writing text outputs without ever leaving a partial file behind.
#pragma once

#include <string>

namespace prism {

// Writes to a temporary file beside `path`, then renames it over `path`. Throws
// std::runtime_error on failure (and removes the temporary file).
void WriteFileAtomically(const std::string &path, const std::string &contents);

}  // namespace prism
