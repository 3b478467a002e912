#include <gtest/gtest.h>

#include "io/comp_channels.h"

namespace clipblur {

namespace {

Image onePixel(const std::vector<std::string>& names, const std::vector<float>& values) {
    Image image = Image::make(1, 1, names);
    for (std::size_t c = 0; c < values.size(); ++c) image.channels[c].values[0] = values[c];
    return image;
}

}  // namespace

// Premultiplied "over": out = fg + (1 - alpha) bg. A pixel half covered by a surface of colour
// (0.6, 0.2, 0) stores (0.3, 0.1, 0) with A = 0.5; over (0.2, 0.4, 0.6) it must read
// (0.3 + 0.1, 0.1 + 0.2, 0 + 0.3) and be opaque.
TEST(CompChannels, BakingIsAnOverOfTheBackground) {
    Image image = onePixel({"R", "G", "B", "A", "coverage"}, {0.3f, 0.1f, 0.0f, 0.5f, 0.5f});
    bakeBackground(image, {0.2, 0.4, 0.6});
    EXPECT_FLOAT_EQ(image.find("R")->values[0], 0.4f);
    EXPECT_FLOAT_EQ(image.find("G")->values[0], 0.3f);
    EXPECT_FLOAT_EQ(image.find("B")->values[0], 0.3f);
    EXPECT_EQ(image.find("A")->values[0], 1.0f);
    EXPECT_EQ(image.find("coverage")->values[0], 0.5f);  // the surfaces' share is kept
}

// 3 px right and 1 px down over a half-frame shutter is 6 px/frame right and 2 px/frame down, so
// v = -2 with y up.
TEST(CompChannels, ForwardVectorsArePixelsPerFrameWithYUp) {
    Image image = onePixel({"R", "G", "B", "A", "motion.x", "motion.y"}, {0, 0, 0, 1, 3.0f, 1.0f});
    toForwardVectors(image, 0.5);
    ASSERT_EQ(image.find("motion.x"), nullptr);
    ASSERT_NE(image.find("forward.u"), nullptr);
    EXPECT_FLOAT_EQ(image.find("forward.u")->values[0], 6.0f);
    EXPECT_FLOAT_EQ(image.find("forward.v")->values[0], -2.0f);

    Image still = onePixel({"R", "G", "B", "A", "motion.x", "motion.y"}, {0, 0, 0, 1, 0.0f, 0.0f});
    toForwardVectors(still, 0.0);  // a zero-length shutter: no motion measured, none invented
    EXPECT_EQ(still.find("forward.u")->values[0], 0.0f);
    EXPECT_EQ(still.find("forward.v")->values[0], 0.0f);
}

}  // namespace clipblur
