#pragma once

#include <string>
#include <string_view>

#include "scene/job.h"

namespace clipblur {

// Output path of one frame: the first run of '#' in `pattern` becomes the zero-padded frame number
// ("out.####.exr", 7 -> "out.0007.exr"); a pattern without '#' names every frame the same file.
std::string expandFramePath(const std::string& pattern, int frame);

// Parses "--frames A-B" or "A" (non-negative, A <= B); throws Error(ExitCode::Usage). Only first and last
// are set: the caller keeps the job's fps.
FrameRange parseFrameRange(std::string_view text);

}  // namespace clipblur
