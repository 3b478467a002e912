#pragma once

#include <string>
#include <string_view>

#include "scene/job.h"

namespace clipblur {

// Output paths name frames with a run of '#': "shot.####.exr" at frame 12 is "shot.0012.exr". Every
// run is replaced, each zero-padded to its own length (longer numbers are not truncated); negative
// frames keep their sign in front of the padding ("-012"). Used by render, merge and submit alike so a
// farm finds exactly the files a local render would write.
bool hasFramePattern(const std::string& pattern);
std::string framePath(const std::string& pattern, int frame);

// The path of frame `frame` for a render of frames [first, last]: the pattern expanded, or the path
// as is for a single frame. Throws Error(ExitCode::Usage) for several frames without a pattern, since
// every frame would overwrite the same file.
std::string outputPathForFrame(const std::string& pattern, int frame, int first, int last);

// Default stats path beside an image: "<image>.stats.json" with the image's extension dropped.
std::string defaultStatsPath(const std::string& image_path);

// Parses "--frames A-B" or "A"; frames may be negative ("-3--1"), A <= B. Throws Error(ExitCode::Usage).
// Only first and last are set: the caller keeps the job's fps.
FrameRange parseFrameRange(std::string_view text);

}  // namespace clipblur
