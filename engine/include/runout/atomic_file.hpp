#pragma once
#include <string>
#include <string_view>

namespace runout {

// Writes contents to path through a temporary file in the same folder and
// rename(2), so readers see the old file or the whole new one, never a part.
// Throws std::runtime_error naming the path on any I/O failure.
void write_file_atomically(const std::string& path, std::string_view contents);

}  // namespace runout
