#include "io/reference_error.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "io/image_files.h"

#include "scene/error.h"

namespace clipblur {

ReferenceImage readReference(const std::string& path, int width, int height) {
    ImageFile file;
    const std::string why = readImageFile(path, ImageRead::HeaderAndPixels, file);
    if (file.format.empty()) throw Error(ExitCode::Config, "cannot read reference image " + path + ": " + why);
    if (file.full_width != width || file.full_height != height)
        throw Error(ExitCode::Config, "reference image " + path + " is " + std::to_string(file.full_width) + "x" +
                                         std::to_string(file.full_height) + ", the render is " +
                                         std::to_string(width) + "x" + std::to_string(height));
    std::array<int, 3> channel{-1, -1, -1};
    const int nc = static_cast<int>(file.channels.size());
    for (int c = 0; c < nc; ++c) {
        const std::string& name = file.channels[static_cast<std::size_t>(c)];
        if (name == "R") channel[0] = c;
        if (name == "G") channel[1] = c;
        if (name == "B") channel[2] = c;
    }
    if (std::find(channel.begin(), channel.end(), -1) != channel.end())
        throw Error(ExitCode::Config, "reference image " + path + " lacks an R, G or B channel");
    if (!why.empty()) throw Error(ExitCode::Config, "cannot read reference image " + path + ": " + why);
    // Pixels outside the reference's data window are black (the EXR convention).
    ReferenceImage ref{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 3, 0.0f)};
    const PixelBounds w = file.window;
    for (int y = 0; y < w.height(); ++y) {
        for (int x = 0; x < w.width(); ++x) {
            const int fx = w.x0 + x - file.full_x, fy = w.y0 + y - file.full_y;
            if (fx < 0 || fy < 0 || fx >= width || fy >= height) continue;
            const std::size_t src = (static_cast<std::size_t>(y) * w.width() + x) * nc;
            for (int k = 0; k < 3; ++k)
                ref.rgb[(static_cast<std::size_t>(fy) * width + fx) * 3 + k] = file.pixels[src + channel[k]];
        }
    }
    return ref;
}

ReferenceError compareWithReference(const Image& image, const ReferenceImage& reference) {
    const std::array<const Image::Channel*, 3> channels{image.find("R"), image.find("G"), image.find("B")};
    ReferenceError e;
    double squares = 0.0, absolutes = 0.0;
    const PixelBounds w = image.window;
    for (int y = w.y0; y < w.y1; ++y) {
        for (int x = w.x0; x < w.x1; ++x) {
            ++e.pixels;
            for (int k = 0; k < 3; ++k) {
                const double d = double(channels[static_cast<std::size_t>(k)]->values[image.index(x, y)]) -
                                 reference.rgb[(static_cast<std::size_t>(y) * reference.width + x) * 3 + k];
                squares += d * d;
                absolutes += std::abs(d);
                e.max_abs = std::max(e.max_abs, std::abs(d));
            }
        }
    }
    const double n = 3.0 * static_cast<double>(std::max<long long>(e.pixels, 1));
    e.rmse = std::sqrt(squares / n);
    e.mean_abs = absolutes / n;
    return e;
}

}  // namespace clipblur
