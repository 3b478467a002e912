#include "renderer/object_coverage.h"

#include <algorithm>

namespace clipblur {

void addShare(ObjectShares& shares, int object, double amount) {
    const auto at = std::lower_bound(shares.begin(), shares.end(), object,
                                     [](const ObjectShare& s, int o) { return s.object < o; });
    if (at != shares.end() && at->object == object)
        at->coverage += amount;
    else
        shares.insert(at, ObjectShare{object, amount});
}

void addShares(ObjectShares& to, const ObjectShares& from, double scale) {
    for (const ObjectShare& s : from) addShare(to, s.object, scale * s.coverage);
}

}  // namespace clipblur
