#include "io/frame_path.h"

#include <charconv>

#include "scene/error.h"

namespace clipblur {

std::string expandFramePath(const std::string& pattern, int frame) {
    const std::size_t start = pattern.find('#');
    if (start == std::string::npos) return pattern;
    std::size_t end = start;
    while (end < pattern.size() && pattern[end] == '#') ++end;
    std::string number = std::to_string(frame < 0 ? -frame : frame);
    if (number.size() < end - start) number.insert(0, end - start - number.size(), '0');
    if (frame < 0) number.insert(0, 1, '-');
    return pattern.substr(0, start) + number + pattern.substr(end);
}

static bool parseNonNegative(std::string_view text, int& value) {
    if (text.empty()) return false;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end && value >= 0;
}

FrameRange parseFrameRange(std::string_view text) {
    const auto usage = [&](const std::string& why) {
        return Error(ExitCode::Usage, "bad frame range \"" + std::string(text) + "\": " + why + " (expected A-B or A)");
    };
    FrameRange range;
    const std::size_t dash = text.find('-');
    if (dash == std::string_view::npos) {
        if (!parseNonNegative(text, range.first)) throw usage("not a non-negative integer");
        range.last = range.first;
        return range;
    }
    if (!parseNonNegative(text.substr(0, dash), range.first) || !parseNonNegative(text.substr(dash + 1), range.last))
        throw usage("not two non-negative integers");
    if (range.last < range.first) throw usage("last frame before first");
    return range;
}

}  // namespace clipblur
