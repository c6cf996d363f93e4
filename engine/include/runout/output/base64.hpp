#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace runout {

// RFC 4648 base64 (with padding), as VTK's XML "binary" format expects.
std::string base64_encode(const void* data, std::size_t size);

// The bytes of one base64 run as base64_encode writes it: a multiple of four
// characters of the alphabet, '=' padding only in its last quantum. Throws
// std::invalid_argument naming the offset of the first character that is
// not so (a frame spoilt on disk, or not written by the engine).
std::string base64_decode(std::string_view text);

}  // namespace runout
