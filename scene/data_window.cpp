#include "scene/data_window.h"

namespace clipblur {

std::string toString(const DataWindow& w) {
    // Appending, not "[" + to_string(...): GCC 12 warns falsely (-Wrestrict, bug 105651) on the latter.
    std::string s = "[";
    s += std::to_string(w.x0);
    s += ",";
    s += std::to_string(w.x1());
    s += ")x[";
    s += std::to_string(w.y0);
    s += ",";
    s += std::to_string(w.y1());
    s += ")";
    return s;
}

}  // namespace clipblur
