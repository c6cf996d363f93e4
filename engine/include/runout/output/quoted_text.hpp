#pragma once
// One string escaper for the text formats the tools write.
#include <string>
#include <string_view>

namespace runout {

// The text in double quotes, with the quote, the backslash, \n and \t
// escaped and every other control character and DEL as \uXXXX: a TOML basic
// string and a JSON string alike (the resolved scene, runout analyse's JSON).
std::string quoted_text(std::string_view text);

}  // namespace runout
