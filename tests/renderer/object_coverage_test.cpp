#include "renderer/object_coverage.h"

#include <gtest/gtest.h>

namespace clipblur {

// Shares stay in increasing object order whatever order objects are met in, and an object met again
// adds to its own share: the order of the per-pixel list never depends on the fragments' order.
TEST(ObjectCoverage, SharesStaySortedAndMergeByObject) {
    ObjectShares a, b;
    addShare(a, 7, 0.25);
    addShare(a, 2, 0.5);
    addShare(a, 7, 0.125);
    addShare(b, 2, 0.5);
    addShare(b, 7, 0.25);
    addShare(b, 7, 0.125);
    ASSERT_EQ(a.size(), 2u);
    EXPECT_EQ(a[0].object, 2);
    EXPECT_EQ(a[1].object, 7);
    EXPECT_EQ(a[1].coverage, 0.375);
    ASSERT_EQ(b.size(), a.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].object, b[i].object);
}

// addShares adds scale x each share, so a weighted sum of per-subframe shares is built as colour is.
TEST(ObjectCoverage, AddSharesScales) {
    ObjectShares total{{1, 0.5}};
    addShares(total, ObjectShares{{0, 1.0}, {1, 0.25}}, 0.5);
    ASSERT_EQ(total.size(), 2u);
    EXPECT_EQ(total[0].object, 0);
    EXPECT_EQ(total[0].coverage, 0.5);
    EXPECT_EQ(total[1].coverage, 0.625);
}

}  // namespace clipblur
