#pragma once

#include <string>
#include <vector>

#include "renderer/image.h"

namespace clipblur {

// An image's R, G, B against a reference render (usually a converged stochastic one), over the
// image's data window.
struct ReferenceError {
    double rmse = 0.0;      // root mean square over every pixel and channel
    double max_abs = 0.0;
    double mean_abs = 0.0;
    long long pixels = 0;
};

// The reference's R, G, B as float over its full display window, row-major. Throws Error(Config) when
// the file cannot be read, lacks R, G or B, or its display window is not width x height.
struct ReferenceImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // 3 per pixel
};
ReferenceImage readReference(const std::string& path, int width, int height);

ReferenceError compareWithReference(const Image& image, const ReferenceImage& reference);

}  // namespace clipblur
