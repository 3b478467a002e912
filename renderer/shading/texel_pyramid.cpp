#include "renderer/shading/texel_pyramid.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

namespace clipblur {

namespace {

// Box resampling of n source cells onto m < n target cells along one axis: target cell i covers source
// [i n/m, (i+1) n/m), each source cell weighted by its overlap, the weights summing to 1.
struct Span {
    int first = 0;
    std::vector<double> weights;
};

std::vector<Span> boxSpans(int n, int m) {
    std::vector<Span> spans(static_cast<std::size_t>(m));
    const double ratio = double(n) / m;
    for (int i = 0; i < m; ++i) {
        const double lo = i * ratio, hi = (i + 1) * ratio;
        Span& s = spans[static_cast<std::size_t>(i)];
        s.first = static_cast<int>(lo);
        for (int k = s.first; k < n && k < hi; ++k)
            s.weights.push_back((std::min(hi, k + 1.0) - std::max(lo, double(k))) / ratio);
    }
    return spans;
}

TexelLevel halve(const TexelLevel& in) {
    TexelLevel out;
    out.width = std::max(1, in.width / 2);
    out.height = std::max(1, in.height / 2);
    const std::vector<Span> xs = boxSpans(in.width, out.width), ys = boxSpans(in.height, out.height);
    // Rows first: `rows` is out.width x in.height.
    std::vector<double> rows(3 * static_cast<std::size_t>(out.width) * static_cast<std::size_t>(in.height));
    for (int j = 0; j < in.height; ++j)
        for (int i = 0; i < out.width; ++i) {
            const Span& s = xs[static_cast<std::size_t>(i)];
            for (std::size_t k = 0; k < s.weights.size(); ++k) {
                const float* t = in.texel(s.first + static_cast<long long>(k), j);
                for (int c = 0; c < 3; ++c) rows[static_cast<std::size_t>(3 * (j * out.width + i) + c)] += s.weights[k] * t[c];
            }
        }
    out.rgb.assign(3 * static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), 0.0f);
    for (int j = 0; j < out.height; ++j)
        for (int i = 0; i < out.width; ++i)
            for (int c = 0; c < 3; ++c) {
                const Span& s = ys[static_cast<std::size_t>(j)];
                double sum = 0.0;
                for (std::size_t k = 0; k < s.weights.size(); ++k)
                    sum += s.weights[k] * rows[3 * ((static_cast<std::size_t>(s.first) + k) * out.width + i) + c];
                out.rgb[static_cast<std::size_t>(3 * (j * out.width + i) + c)] = static_cast<float>(sum);
            }
    return out;
}

}  // namespace

TexelPyramid::TexelPyramid(ImageTextures::Texels finest) {
    if (finest.width <= 0 || finest.height <= 0 ||
        finest.rgb.size() != 3 * static_cast<std::size_t>(finest.width) * static_cast<std::size_t>(finest.height))
        return;
    levels_.push_back({finest.width, finest.height, std::move(finest.rgb)});
    while (levels_.back().width > 1 || levels_.back().height > 1) levels_.push_back(halve(levels_.back()));
}

const TexelPyramid& TexelPyramid::of(const ImageTextures::Image& image) {
    static std::mutex mutex;
    static std::map<const ImageTextures::Image*, std::unique_ptr<TexelPyramid>> built;
    const std::lock_guard lock(mutex);
    std::unique_ptr<TexelPyramid>& slot = built[&image];
    if (!slot) slot = std::make_unique<TexelPyramid>(ImageTextures::shared().texels(image));
    return *slot;
}

}  // namespace clipblur
