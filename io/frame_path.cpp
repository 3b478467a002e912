#include "io/frame_path.h"

#include <charconv>
#include <filesystem>

#include "io/config/job_schema.h"
#include "scene/error.h"

namespace clipblur {

bool hasFramePattern(const std::string& pattern) { return pattern.find('#') != std::string::npos; }

std::string framePath(const std::string& pattern, int frame) {
    const long long value = frame;
    const std::string digits = std::to_string(value < 0 ? -value : value);
    std::string out;
    for (std::size_t i = 0; i < pattern.size();) {
        if (pattern[i] != '#') {
            out += pattern[i++];
            continue;
        }
        std::size_t width = 0;
        while (i < pattern.size() && pattern[i] == '#') {
            ++width;
            ++i;
        }
        if (value < 0) out += '-';
        if (digits.size() < width) out.append(width - digits.size(), '0');
        out += digits;
    }
    return out;
}

std::string outputPathForFrame(const std::string& pattern, int frame, int first, int last) {
    if (hasFramePattern(pattern)) return framePath(pattern, frame);
    if (first != last)
        throw Error(ExitCode::Usage, "output path '" + pattern + "' has no #### frame pattern but frames " +
                                         std::to_string(first) + "-" + std::to_string(last) +
                                         " are rendered; every frame would overwrite the same file");
    return pattern;
}

std::string defaultStatsPath(const std::string& image_path) {
    std::filesystem::path p(image_path);
    p.replace_extension();
    return p.string() + ".stats.json";
}

FrameRange parseFrameRange(std::string_view text) {
    const auto usage = [&](const std::string& why) {
        return Error(ExitCode::Usage, "bad frame range \"" + std::string(text) + "\": " + why + " (expected A-B or A)");
    };
    const char* const end = text.data() + text.size();
    FrameRange range;
    // from_chars takes a leading '-' as the sign, so "-3--1" reads -3, then the separator, then -1.
    std::from_chars_result r = std::from_chars(text.data(), end, range.first);
    if (r.ec == std::errc::result_out_of_range) throw usage("frame number out of range");
    if (r.ec != std::errc()) throw usage("not an integer");
    if (r.ptr == end) {
        range.last = range.first;
    } else {
        if (*r.ptr != '-') throw usage("not an integer");
        r = std::from_chars(r.ptr + 1, end, range.last);
        if (r.ec == std::errc::result_out_of_range) throw usage("frame number out of range");
        if (r.ec != std::errc() || r.ptr != end) throw usage("not two integers");
        if (range.last < range.first) throw usage("last frame before first");
    }
    // The job schema's limits (docs/config.md), which also keep a frame loop's `int` from overflowing.
    if (range.first < -config::kMaxFrameCount || range.last > config::kMaxFrameCount)
        throw usage("frame numbers must be within -" + std::to_string(config::kMaxFrameCount) + ".." +
                    std::to_string(config::kMaxFrameCount));
    if (static_cast<long long>(range.last) - range.first >= config::kMaxFrameCount)
        throw usage("more than " + std::to_string(config::kMaxFrameCount) + " frames");
    return range;
}

}  // namespace clipblur
