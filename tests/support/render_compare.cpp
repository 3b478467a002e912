#include "support/render_compare.h"

namespace clipblur::testing {

double meanSquaredDifference(const RenderResult& a, const RenderResult& b, const RenderResult* c,
                             const std::vector<bool>& mask) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const char* name : {"R", "G", "B"}) {
        const auto& x = a.image.find(name)->values;
        const auto& y = b.image.find(name)->values;
        for (std::size_t i = 0; i < x.size(); ++i) {
            if (!mask.empty() && !mask[i]) continue;
            const double ref = c ? 0.5 * (double(y[i]) + c->image.find(name)->values[i]) : y[i];
            sum += (x[i] - ref) * (x[i] - ref);
            ++n;
        }
    }
    return n ? sum / double(n) : 0.0;
}

RenderResult averaged(const RenderResult& a, const RenderResult& b) {
    RenderResult m = a;
    for (std::size_t c = 0; c < m.image.channels.size(); ++c)
        for (std::size_t i = 0; i < m.image.channels[c].values.size(); ++i)
            m.image.channels[c].values[i] = 0.5f * (a.image.channels[c].values[i] + b.image.channels[c].values[i]);
    return m;
}

}  // namespace clipblur::testing
