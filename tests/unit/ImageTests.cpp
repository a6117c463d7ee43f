#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <thread>
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
    EXPECT_THROW(compareImages(a, Image::fromTexels(1, 1, Format::RGBA8, {{0, 0, 0, 1}}), 0.1),
                 Error);
}

// A rounding tie (0.5 is 127.5 steps) may land on either side on a real GPU (NVIDIA: 127,
// lavapipe: 128): a tolerance of one 8-bit step takes every value one step off, as decoded
// floats, and nothing two steps off.
TEST(Image, ToleranceOfWholeStepsHoldsForEveryEightBitValue) {
    for (int v = 1; v < 255; ++v) {
        const float lo = float(v - 1) / 255.0f, mid = float(v) / 255.0f, hi = float(v + 1) / 255.0f;
        const Image a = Image::fromTexels(1, 1, Format::RGBA8, {{mid, mid, mid, 1}});
        EXPECT_EQ(compareImages(a, Image::fromTexels(1, 1, Format::RGBA8, {{lo, hi, mid, 1}}),
                                1.0 / 255.0)
                      .pixelsOverTolerance,
                  0u)
            << v;
        if (v > 1) {
            EXPECT_EQ(compareImages(a,
                                    Image::fromTexels(1, 1, Format::RGBA8,
                                                      {{float(v - 2) / 255.0f, mid, mid, 1}}),
                                    1.0 / 255.0)
                          .pixelsOverTolerance,
                      1u)
                << v;
        }
    }
}

TEST(Image, PfmIsBottomRowFirstLittleEndian) {
    Image img =
        Image::fromTexels(1, 2, Format::RGBA32F, {{1, 2, 3, 1}, {4, 5, 6, 1}});  // top, bottom
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

// A command list keeps a pointer to its bound pipeline while the renderer may create more
// objects, on this thread or another: growing a pool must not move the ones it holds.
TEST(HandlePool, ObjectsDoNotMoveWhenThePoolGrows) {
    struct Big {
        int value = 0;
        char payload[3000] = {};  // a pipeline-sized object: few slots per chunk
    };
    HandlePool<PipelineHandle, Big> pool;
    PipelineHandle first = pool.add(Big{7});
    const Big* where = pool.find(first);
    std::vector<PipelineHandle> more;
    for (int i = 0; i < 1000; ++i) more.push_back(pool.add(Big{i}));
    EXPECT_EQ(pool.find(first), where);
    EXPECT_EQ(pool.find(first)->value, 7);
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(pool.get(more[size_t(i)], "pipeline").value, i);
    int visited = 0;
    pool.forEach([&](Big&) { ++visited; });
    EXPECT_EQ(visited, 1001);
    EXPECT_EQ(pool.find(PipelineHandle{}), nullptr);                    // id 0: never valid
    EXPECT_EQ(pool.find(PipelineHandle{(1u << 20) | 2000u}), nullptr);  // index past the end
}

TEST(HandlePool, FindsEveryObjectAfterGrowing) {
    HandlePool<BufferHandle, int> pool;
    std::vector<BufferHandle> handles;
    for (int i = 0; i < 1000; ++i) handles.push_back(pool.add(int(i)));
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(pool.get(handles[size_t(i)], "buffer"), i);
    int out = 0;
    EXPECT_TRUE(pool.remove(handles[500], out));
    EXPECT_EQ(out, 500);
    EXPECT_EQ(pool.find(handles[500]), nullptr);
    EXPECT_FALSE(pool.remove(handles[500], out));
}

// Command lists look handles up on recording threads while another thread creates objects:
// lookups must see every published object and never a moved or half-written one (the
// ThreadSanitizer step runs this too).
TEST(HandlePool, LookupsOnOtherThreadsWhileOneThreadAdds) {
    HandlePool<BufferHandle, int> pool;
    const BufferHandle first = pool.add(42);
    std::atomic<bool> done{false};
    std::atomic<uint32_t> mismatches{0};
    std::thread reader([&] {
        while (!done.load()) {
            const int* v = pool.find(first);
            if (!v || *v != 42) mismatches++;
        }
    });
    std::vector<BufferHandle> added;
    for (int i = 0; i < 20000; ++i) added.push_back(pool.add(int(i)));
    done = true;
    reader.join();
    EXPECT_EQ(mismatches.load(), 0u);
    for (int i = 0; i < 20000; ++i) ASSERT_EQ(*pool.find(added[size_t(i)]), i);
}

// retire() invalidates the handle at once; at() still reaches the object until release().
TEST(HandlePool, RetiredObjectsStayReachableUntilReleased) {
    HandlePool<BufferHandle, int> pool;
    const BufferHandle h = pool.add(7);
    EXPECT_TRUE(pool.retire(h));
    EXPECT_EQ(pool.find(h), nullptr);
    EXPECT_FALSE(pool.retire(h));
    EXPECT_EQ(pool.at(h), 7);
    int out = 0;
    pool.release(h, out);
    EXPECT_EQ(out, 7);
    const BufferHandle next = pool.add(8);  // reuses the slot with a new generation
    EXPECT_EQ(pool.find(h), nullptr);
    EXPECT_EQ(*pool.find(next), 8);
}
