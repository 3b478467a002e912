#pragma once

#include <string>

#include "renderer/image_file.h"

namespace clipblur {

class ImageTextures;

// What libclipblur_oiio.so, the one place OpenImageIO is linked, provides. Debian's OpenImageIO pulls in
// some 250 shared libraries (FFmpeg, OpenCV, GDAL, ...) whose loading and relocation cost 0.15-0.4 s
// (and, on a thread beside a render, took a sixth of its CPU); so the executable does not link it, and
// only a process that uses textures or an image format other than OpenEXR and PNG (io/image_files.h)
// loads the module, on first use. Built by the same compiler from the same headers as the executable.
struct ImageModule {
    // Reads `file`'s first subimage into `out`; empty on success, else why not. When the header reads
    // but the pixels do not (a truncated file), `out` holds the header (its `format` is set).
    std::string (*read)(const std::string& file, ImageRead what, ImageFile& out);
    // Writes `image` to `file`, the format following its extension; empty on success, else why not.
    std::string (*write)(const std::string& file, const ImageFile& image);
    // The process's one texture system.
    ImageTextures& (*textures)();
};

// Loads the module once (thread-safe): from beside the executable, else from where the build put it.
// Throws Error(ExitCode::Output) naming the file and the loader's reason when it cannot be loaded.
const ImageModule& imageModule();

}  // namespace clipblur
