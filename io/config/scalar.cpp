#include "io/config/scalar.h"

#include <charconv>
#include <cmath>

namespace clipblur::config {

namespace {

// from_chars rejects a leading '+', which YAML and humans write; JSON never produces one.
std::string_view stripPlus(const std::string& text) {
    std::string_view v(text);
    if (v.size() > 1 && v.front() == '+' && v[1] != '-') v.remove_prefix(1);
    return v;
}

}  // namespace

std::optional<double> parseNumber(const std::string& text) {
    const std::string_view v = stripPlus(text);
    if (v.empty()) return std::nullopt;
    // Reject the spellings from_chars accepts that are not numbers in a config file.
    const char c0 = v.front() == '-' ? (v.size() > 1 ? v[1] : '\0') : v.front();
    if (!(c0 >= '0' && c0 <= '9') && c0 != '.') return std::nullopt;
    double d = 0.0;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), d);
    if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(d)) return std::nullopt;
    return d;
}

std::optional<std::int64_t> parseInteger(const std::string& text) {
    const std::string_view v = stripPlus(text);
    std::int64_t i = 0;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), i);
    if (v.empty() || r.ec != std::errc() || r.ptr != v.data() + v.size()) return std::nullopt;
    return i;
}

std::optional<std::uint64_t> parseUnsigned(const std::string& text) {
    const std::string_view v = stripPlus(text);
    std::uint64_t u = 0;
    if (v.empty() || v.front() == '-') return std::nullopt;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), u);
    if (r.ec != std::errc() || r.ptr != v.data() + v.size()) return std::nullopt;
    return u;
}

std::optional<bool> parseBool(const std::string& text) {
    if (text == "true") return true;
    if (text == "false") return false;
    return std::nullopt;
}

}  // namespace clipblur::config
