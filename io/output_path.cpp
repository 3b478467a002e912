#include "io/output_path.h"

#include <cstdlib>
#include <filesystem>

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

}  // namespace clipblur
