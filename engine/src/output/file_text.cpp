#include "runout/output/file_text.hpp"

#include <fstream>
#include <iterator>
#include <stdexcept>

namespace runout {

std::optional<std::string> file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::optional<std::string> regular_file_text(const std::filesystem::path& path) {
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(path, ignored)) return std::nullopt;
  return file_text(path);
}

std::string file_text_or_throw(const std::filesystem::path& path, const std::string& error) {
  std::optional<std::string> text = file_text(path);
  if (!text) throw std::runtime_error(error);
  return std::move(*text);
}

}  // namespace runout
