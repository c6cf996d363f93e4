#pragma once
#include <cstddef>
#include <string>

namespace runout {

// RFC 4648 base64 (with padding), as VTK's XML "binary" format expects.
std::string base64_encode(const void* data, std::size_t size);

}  // namespace runout
