#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace clipblur::config {

// Strict scalar conversions: the whole text must be consumed, and only finite numbers count
// (std::from_chars would otherwise accept "nan" and "inf").
std::optional<double> parseNumber(const std::string& text);
std::optional<std::int64_t> parseInteger(const std::string& text);
std::optional<std::uint64_t> parseUnsigned(const std::string& text);
std::optional<bool> parseBool(const std::string& text);

}  // namespace clipblur::config
