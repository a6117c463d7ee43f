// The conformance suite can fail: its runner rejects wrong images and exceptions (validation
// errors are counted by the same runner), and every analytic expectation catches a corrupted image.
#include <gtest/gtest.h>

#include "BackendTest.h"
#include "Conformance.h"

using namespace fe;

class ConformanceRunner : public fe::testing::BackendTest {};

TEST_P(ConformanceRunner, RejectsWrongImagesAndExceptions) {
    const gdi::Image grey = gdi::Image::fromTexels(
        4, 4, gdi::Format::RGBA8, std::vector<std::array<float, 4>>(16, {0.5f, 0.5f, 0.5f, 1}));
    const gdi::Image black = gdi::Image::fromTexels(
        4, 4, gdi::Format::RGBA8, std::vector<std::array<float, 4>>(16, {0, 0, 0, 1}));
    conformance::Case right{"right", [&](gdi::Device&) {
                                return std::vector<conformance::CaseImage>{{"img", grey, grey}};
                            }};
    conformance::Case wrong{"wrong", [&](gdi::Device&) {
                                return std::vector<conformance::CaseImage>{{"img", black, grey}};
                            }};
    conformance::Case throws{"throws", [](gdi::Device& d) -> std::vector<conformance::CaseImage> {
                                 d.createBuffer({.size = 0});  // invalid description
                                 return {};
                             }};
    EXPECT_TRUE(conformance::runCase(*device, right).passed);
    conformance::CaseResult r = conformance::runCase(*device, wrong);
    EXPECT_FALSE(r.passed);
    EXPECT_NE(r.message.find("16 of 16 pixels off"), std::string::npos) << r.message;
    r = conformance::runCase(*device, throws);
    EXPECT_FALSE(r.passed);
    EXPECT_NE(r.message.find("size is 0"), std::string::npos) << r.message;

    conformance::Case checks{"checks", [](gdi::Device&) -> std::vector<conformance::CaseImage> {
                                 const double measured = 0.0;
                                 FE_CONFORMANCE_CHECK(measured > 0.0, "a non-zero duration");
                                 return {};
                             }};
    r = conformance::runCase(*device, checks);
    EXPECT_FALSE(r.passed);
    EXPECT_NE(r.message.find("ConformanceRunnerTests.cpp:"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("check failed: a non-zero duration (measured > 0.0)"),
              std::string::npos)
        << r.message;
}

// Every real case: its analytic expectations pass as rendered, and fail once 2 % of the
// rendered pixels are pushed by 0.5 (so no expectation is vacuous or too loose).
TEST_P(ConformanceRunner, EveryAnalyticExpectationCatchesACorruptedImage) {
    int checked = 0;
    for (const conformance::Case& c : conformance::cases()) {
        conformance::CaseResult r = conformance::runCase(*device, c);
        EXPECT_TRUE(r.passed) << c.name << ": " << r.message;
        for (conformance::CaseImage& ci : r.images) {
            if (ci.expected.data.empty()) continue;
            std::vector<std::array<float, 4>> texels;
            for (uint32_t y = 0; y < ci.image.height; ++y)
                for (uint32_t x = 0; x < ci.image.width; ++x) {
                    auto t = ci.image.texel(x, y);
                    if ((x * 7 + y * 13) % 50 == 0)
                        for (int k = 0; k < 4; ++k) t[k] = t[k] > 0.5f ? t[k] - 0.5f : t[k] + 0.5f;
                    texels.push_back(t);
                }
            gdi::Image corrupted =
                gdi::Image::fromTexels(ci.image.width, ci.image.height, ci.image.format, texels);
            gdi::ImageDiff d = gdi::compareImages(corrupted, ci.expected, ci.absTolerance);
            EXPECT_GT(d.fractionOver(), ci.maxFractionOver)
                << c.name << "/" << ci.name << " accepts a corrupted image";
            ++checked;
        }
    }
    EXPECT_GT(checked, 20);  // the suite has analytic expectations to check
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(ConformanceRunner);
