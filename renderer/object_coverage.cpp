#include "renderer/object_coverage.h"

#include <algorithm>

namespace clipblur {

void addShare(std::vector<ObjectShare>& shares, int object, double amount) {
    const auto at = std::lower_bound(shares.begin(), shares.end(), object,
                                     [](const ObjectShare& s, int o) { return s.object < o; });
    if (at != shares.end() && at->object == object)
        at->coverage += amount;
    else
        shares.insert(at, ObjectShare{object, amount});
}

}  // namespace clipblur
