#pragma once
// A whole file read into memory: the one reader of the indexes, manifests,
// summaries, histories, frames and images the engine and the CLI read back.
// Each caller says in its own words what a file it cannot read means.
#include <filesystem>
#include <optional>
#include <string>

namespace runout {

// The bytes of the file at `path`, as they are; nullopt where it cannot be
// opened.
std::optional<std::string> file_text(const std::filesystem::path& path);

// file_text of a regular file; nullopt, without opening it, for a path that
// is not one (missing, a folder, a device, a pipe: a device would never end).
std::optional<std::string> regular_file_text(const std::filesystem::path& path);

// file_text, or std::runtime_error(error) where the file cannot be opened.
std::string file_text_or_throw(const std::filesystem::path& path, const std::string& error);

}  // namespace runout
