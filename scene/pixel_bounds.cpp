#include "scene/pixel_bounds.h"

namespace clipblur {

std::string toString(const PixelBounds& b) {
    // Appending, not "[" + to_string(...): GCC 12 warns falsely (-Wrestrict, bug 105651) on the latter.
    std::string s = "[";
    s += std::to_string(b.x0);
    s += ",";
    s += std::to_string(b.x1);
    s += ")x[";
    s += std::to_string(b.y0);
    s += ",";
    s += std::to_string(b.y1);
    s += ")";
    return s;
}

}  // namespace clipblur
