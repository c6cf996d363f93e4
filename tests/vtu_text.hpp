#pragma once
// A frame's arrays read from its XML text without VTK: the base64 text of
// a named <DataArray>, decoded (test_vtu_writer, test_guards).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace runout::vtu_text {

inline std::string decode_base64(const std::string& text) {
  static const std::string alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned bits = 0;
  int count = 0;
  for (const char c : text) {
    if (c == '=') break;
    const auto v = alphabet.find(c);
    if (v == std::string::npos) throw std::runtime_error("not base64");
    bits = bits << 6 | static_cast<unsigned>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>(bits >> count & 0xff);
    }
  }
  return out;
}

// The base64 text inside <DataArray ... Name="name" ...>.
inline std::string array_text(const std::string& xml, const std::string& name) {
  const auto at = xml.find("Name=\"" + name + "\"");
  if (at == std::string::npos) throw std::runtime_error("no array " + name);
  const auto begin = xml.find('>', at) + 1;
  const auto end = xml.find("</DataArray>", begin);
  std::string text = xml.substr(begin, end - begin);
  text.erase(std::remove_if(text.begin(), text.end(), ::isspace), text.end());
  return text;
}

template <class T>
inline std::vector<T> as_values(const std::string& bytes) {
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

// Uncompressed: base64(UInt64 byte count, bytes).
inline std::string decode_raw(const std::string& text) {
  const std::string all = decode_base64(text);
  const auto size = as_values<std::uint64_t>(all.substr(0, 8)).at(0);
  EXPECT_EQ(size, all.size() - 8);
  return all.substr(8);
}

}  // namespace runout::vtu_text
