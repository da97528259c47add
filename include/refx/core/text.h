// Small text helpers shared by refx's parsers (caps files, scene scripts, state names).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace refx {

// Without leading and trailing white space.
std::string_view trim(std::string_view s);
bool equalsNoCase(std::string_view a, std::string_view b);
bool startsWithNoCase(std::string_view s, std::string_view prefix);
std::string toUpper(std::string_view s);
std::string toLower(std::string_view s);
// Decimal or 0x-prefixed hexadecimal, the whole string; nullopt when malformed or
// out of range.
std::optional<uint64_t> parseUnsigned(std::string_view s);

}  // namespace refx
