#include "runout/output/base64.hpp"

#include <stdexcept>

namespace runout {

namespace {

constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// The 6-bit value of a base64 character, -1 for any other.
int sextet(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

}  // namespace

std::string base64_encode(const void* data, std::size_t size) {
  const auto* in = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);

  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const unsigned v = in[i] << 16 | in[i + 1] << 8 | in[i + 2];
    out += alphabet[v >> 18 & 63];
    out += alphabet[v >> 12 & 63];
    out += alphabet[v >> 6 & 63];
    out += alphabet[v & 63];
  }
  // One or two bytes left: pad the last quantum with '=' (RFC 4648 s. 4).
  if (const std::size_t left = size - i; left > 0) {
    const unsigned v = in[i] << 16 | (left == 2 ? in[i + 1] << 8 : 0);
    out += alphabet[v >> 18 & 63];
    out += alphabet[v >> 12 & 63];
    out += left == 2 ? alphabet[v >> 6 & 63] : '=';
    out += '=';
  }
  return out;
}

std::string base64_decode(std::string_view text) {
  if (text.size() % 4 != 0)
    throw std::invalid_argument("base64 of " + std::to_string(text.size()) +
                                " characters, not a multiple of 4");
  std::string out;
  out.reserve(text.size() / 4 * 3);
  for (std::size_t at = 0; at < text.size(); at += 4) {
    const bool last = at + 4 == text.size();
    // '=' pads the last quantum only, as its third and fourth or its
    // fourth character.
    const int pad = last && text[at + 3] == '=' ? (text[at + 2] == '=' ? 2 : 1) : 0;
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      const int bits = k < 4 - pad ? sextet(text[at + k]) : 0;
      if (bits < 0)
        throw std::invalid_argument("a character that is not base64 at offset " +
                                    std::to_string(at + k));
      v = v << 6 | static_cast<unsigned>(bits);
    }
    out += static_cast<char>(v >> 16 & 0xff);
    if (pad < 2) out += static_cast<char>(v >> 8 & 0xff);
    if (pad < 1) out += static_cast<char>(v & 0xff);
  }
  return out;
}

}  // namespace runout
