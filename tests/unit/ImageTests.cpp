#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "fe/gdi/HandlePool.h"
#include "fe/gdi/Image.h"

using namespace fe::gdi;

TEST(Image, HalfAndSmallFloatRoundTrip) {
    for (Format f : {Format::RGBA16F, Format::R11G11B10F, Format::RGBA32F, Format::RGBA8}) {
        Image img = Image::fromTexels(1, 1, f, {{0.5f, 0.25f, 1.0f, 1.0f}});
        auto t = img.texel(0, 0);
        EXPECT_NEAR(t[0], 0.5f, 2e-3) << formatInfo(f).name;
        EXPECT_NEAR(t[1], 0.25f, 2e-3) << formatInfo(f).name;
        EXPECT_NEAR(t[2], 1.0f, 2e-3) << formatInfo(f).name;
    }
}

TEST(Image, CompareCountsPixelsOverTolerance) {
    Image a = Image::fromTexels(2, 1, Format::RGBA8, {{0, 0, 0, 1}, {1, 1, 1, 1}});
    Image b = Image::fromTexels(2, 1, Format::RGBA8, {{0, 0, 0, 1}, {0.5f, 1, 1, 1}});
    ImageDiff d = compareImages(a, b, 5.0 / 255.0);
    EXPECT_EQ(d.pixelsOverTolerance, 1u);
    EXPECT_NEAR(d.maxAbsError, 0.5, 0.01);
    EXPECT_THROW(compareImages(a, Image::fromTexels(1, 1, Format::RGBA8, {{0, 0, 0, 1}}), 0.1), Error);
}

TEST(Image, PfmIsBottomRowFirstLittleEndian) {
    Image img = Image::fromTexels(1, 2, Format::RGBA32F, {{1, 2, 3, 1}, {4, 5, 6, 1}});  // top, bottom
    const std::string path = ::testing::TempDir() + "/t.pfm";
    writePfm(img, path);
    std::ifstream f(path, std::ios::binary);
    std::string magic, dims, scale;
    std::getline(f, magic);
    std::getline(f, dims);
    std::getline(f, scale);
    EXPECT_EQ(magic, "PF");
    EXPECT_EQ(dims, "1 2");
    EXPECT_EQ(scale, "-1.0");
    float first[3];
    f.read(reinterpret_cast<char*>(first), sizeof first);
    EXPECT_EQ(first[0], 4.0f);  // the bottom row comes first
}

TEST(Format, TableIsConsistent) {
    EXPECT_EQ(formatInfo(Format::RGBA16F).bytesPerPixel, 8u);
    EXPECT_TRUE(formatInfo(Format::D24S8).hasStencil);
    EXPECT_EQ(formatFromName("R11G11B10F"), Format::R11G11B10F);
    EXPECT_EQ(formatFromName("nope"), Format::Undefined);
}

TEST(HandlePool, StaleHandlesAreRejected) {
    HandlePool<BufferHandle, int> pool;
    BufferHandle a = pool.add(1);
    int out;
    EXPECT_TRUE(pool.remove(a, out));
    BufferHandle b = pool.add(2);
    EXPECT_EQ(pool.find(a), nullptr);  // same slot, new generation
    ASSERT_NE(pool.find(b), nullptr);
    EXPECT_EQ(*pool.find(b), 2);
    EXPECT_THROW(pool.get(a, "buffer"), Error);
}
