#pragma once

#include <string>

#include "renderer/image_file.h"

namespace clipblur {

// OpenEXR files through the OpenEXR library itself, linked into the executable: its closure is a dozen
// small libraries (about 1.5 ms to load), where OpenImageIO's is some 260 (0.15-0.4 s of dynamic
// loading, image_module.h). OpenImageIO reads these files as it reads its own (tests/io check that).
//
// Attributes keep OpenEXR's names and types (int, float, string and string vector, m44f, rational,
// v2f, v3f, v2i, float vector, chromaticities as float[8]); `compression` is the header's compression
// as its name (zip, piz, dwaa, none, ...). The structural attributes (windows, channels, line order,
// screen window, pixel aspect, type) are not attributes here: they are ImageFile's fields or the
// defaults every clipblur file has. Channels read in the order OpenImageIO gives them: those without a
// layer first, then the layers by name, each with R, G, B, A first and the rest by name.

// Reads `file` into `out`; empty on success, else why not. When the header reads but the pixels do not
// (a file cut short), `out` holds the header (its `format` is set).
std::string readExrFile(const std::string& file, ImageRead what, ImageFile& out);

// Writes `image` as a scanline OpenEXR file; empty on success, else why not (nothing is then left at
// `file` unless a partial file was written, which the caller's atomic write removes).
std::string writeExrFile(const std::string& file, const ImageFile& image);

}  // namespace clipblur
