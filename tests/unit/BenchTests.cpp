// The bench (integration/Bench.h): a small sweep on each backend writes every figure the schema
// promises, the CSV carries the same records, sweep files are checked, and a comparison flags
// a slower frame or a less exact image as a regression.
#include <chrono>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "BackendTest.h"
#include "integration/Bench.h"
#include "render/TechniqueRenderer.h"

using namespace fe;

namespace {
std::vector<render::BenchCase> tinySweep() {
    return render::sweepFromJson(gdi::Json::parse(R"({"cases": [
        {"scene": "builtin:spheres", "technique": "forward", "size": "48x36", "sphereGrid": 3},
        {"scene": "builtin:spheres", "technique": "redeferred", "size": "48x36", "sphereGrid": 3, "illumScale": 4},
        {"scene": "builtin:shadows", "technique": "deferred", "size": "48x36", "shadows": true, "shadowMapSize": 256,
         "environment": "builtin:sky", "iblPrefiltered": true}]})"));
}

class Bench : public fe::testing::BackendTest {};
}  // namespace

TEST_P(Bench, SweepRecordsTimesMemoryAndError) {
    device.reset();  // the bench opens the backend itself
    // Each measurement hands over the document so far (fe bench writes results.partial.json).
    std::vector<size_t> partialSizes;
    const gdi::Json doc = render::runBench(tinySweep(), {GetParam()},
                                           {.warmupFrames = 1,
                                            .frames = 3,
                                            .validation = true,
                                            .onResult = [&](const gdi::Json& partial) {
                                                partialSizes.push_back(partial["results"].size());
                                            }});
    EXPECT_EQ(partialSizes, (std::vector<size_t>{1, 2, 3}));
    EXPECT_EQ(doc["schema"], "fe-results/1");
    EXPECT_TRUE(doc["engine"].contains("commit"));
    ASSERT_EQ(doc["backends"].size(), 1u);
    EXPECT_TRUE(doc["backends"][0]["available"].get<bool>());
    EXPECT_EQ(doc["backends"][0]["validationErrors"], 0u);
    ASSERT_EQ(doc["results"].size(), 3u);
    for (const gdi::Json& r : doc["results"]) {
        SCOPED_TRACE(r["key"].get<std::string>());
        ASSERT_FALSE(r.contains("refused")) << r["refused"];
        EXPECT_EQ(r["cpuFrameMs"]["samples"], 3u);
        EXPECT_GT(r["cpuFrameMs"]["median"].get<double>(), 0.0);
        EXPECT_LE(r["cpuFrameMs"]["min"].get<double>(), r["cpuFrameMs"]["max"].get<double>());
        EXPECT_GT(r["memory"]["transientWithoutAliasing"].get<uint64_t>(), 0u);
        EXPECT_FALSE(r["memory"]["textures"].empty());
        for (const char* k : {"ssim", "flip", "percentOver5", "maxAbs"})
            EXPECT_TRUE(r["error"][k].is_number()) << k;
        EXPECT_TRUE(r["settings"].contains("shadows"));
    }
    // Forward is exact; the reduced rate is not; the reference knew about shadows and the sky.
    EXPECT_GT(doc["results"][0]["error"]["psnr"].get<double>(), 45.0);
    EXPECT_LT(doc["results"][0]["error"]["percentOver5"].get<double>(), 0.5);
    EXPECT_GT(doc["results"][1]["error"]["percentOver5"].get<double>(), 1.0);
    EXPECT_EQ(doc["results"][2]["reference"],
              "cpu reference, image-based lighting at 4096 samples, shadow rays");
    EXPECT_LT(doc["results"][2]["error"]["flip"].get<double>(), 0.1);
    // Each against its own BRDF's exact image, and against glTF's: the same for forward (glTF's
    // own), farther for redeferred (the separable BRDF) than its own.
    EXPECT_EQ(doc["results"][0]["brdf"], "gltf");
    EXPECT_EQ(doc["results"][0]["errorAgainstGltf"], doc["results"][0]["error"]);
    EXPECT_EQ(doc["results"][1]["brdf"], "separable");
    EXPECT_GT(doc["results"][1]["errorAgainstGltf"]["percentOver5"].get<double>(),
              doc["results"][1]["error"]["percentOver5"].get<double>());
    const std::string csv = render::resultsCsv(doc);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
    EXPECT_NE(csv.find(GetParam() + ",spheres/redeferred/scale4/48x36,"), std::string::npos) << csv;
    // Against itself nothing regresses; a doubled frame time or 1 point more error does.
    EXPECT_FALSE(render::compareResults(doc, doc).regression);
    gdi::Json slower = doc, worse = doc;
    slower["results"][1]["cpuFrameMs"]["median"] =
        doc["results"][1]["cpuFrameMs"]["median"].get<double>() * 2.0;
    worse["results"][0]["error"]["percentOver5"] =
        doc["results"][0]["error"]["percentOver5"].get<double>() + 1.0;
    const render::BenchComparison s = render::compareResults(doc, slower),
                                  w = render::compareResults(doc, worse);
    EXPECT_TRUE(s.regression);
    EXPECT_NE(s.report.find("redeferred/scale4/48x36: frame time x2.00"), std::string::npos)
        << s.report;
    EXPECT_TRUE(w.regression);
    EXPECT_NE(w.report.find("LESS EXACT"), std::string::npos) << w.report;
    EXPECT_FALSE(
        render::compareResults(doc, slower, 2.5).regression);  // the threshold is the user's
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(Bench);

// A GPU idling between waited frames stays at its lowest clock (an H200 ran two-frame warm-ups
// at 5x its fastest frame), so on hardware the warm-up also lasts BenchOptions::warmupSeconds;
// a software rasterizer has no clock to raise and keeps to warmupFrames.
TEST_P(Bench, WarmUpLastsItsTimeOnAGpuAndItsFramesOnASoftwareDevice) {
    const bool software = device->info().softwareRasterizer;
    device.reset();
    std::vector<render::BenchCase> cases = tinySweep();
    cases.resize(1);
    std::vector<std::chrono::steady_clock::time_point> frames;
    render::BenchOptions options{.warmupFrames = 1, .warmupSeconds = 0.3, .frames = 2};
    options.onFrame = [&](const std::string&, uint32_t) {
        frames.push_back(std::chrono::steady_clock::now());
    };
    render::runBench(cases, {GetParam()}, options);
    ASSERT_GE(frames.size(), 3u);
    if (software) {
        EXPECT_EQ(frames.size(), 3u) << "a software device warmed up for a time";
    } else {
        // The first timed frame starts after the warm-up's time. Its clock starts before frame
        // 0, whose end is the first time seen here: one frame's time is allowed for that.
        const double warm =
            std::chrono::duration<double>(frames[frames.size() - 2] - frames[0]).count();
        double longest = 0;
        for (size_t i = 1; i + 1 < frames.size(); ++i)
            longest =
                std::max(longest, std::chrono::duration<double>(frames[i] - frames[i - 1]).count());
        EXPECT_GE(warm + longest, 0.3) << frames.size() << " frames";
    }
}

// --interleave: frame f of every case, then frame f + 1; the same images and sample counts as
// one case after another.
TEST_P(Bench, InterleavedCasesAlternateFramesAndMeasureTheSame) {
    device.reset();
    std::vector<render::BenchCase> cases = tinySweep();
    cases.resize(2);
    std::vector<std::string> sequential, interleaved;
    // Counted frames only: a GPU's timed warm-up would add frames (WarmUp, below).
    render::BenchOptions options{
        .warmupFrames = 1, .warmupSeconds = 0, .frames = 2, .validation = true};
    options.onFrame = [&](const std::string& key, uint32_t f) {
        sequential.push_back(key + " " + std::to_string(f));
    };
    const gdi::Json a = render::runBench(cases, {GetParam()}, options);
    options.interleave = true;
    options.onFrame = [&](const std::string& key, uint32_t f) {
        interleaved.push_back(key + " " + std::to_string(f));
    };
    const gdi::Json b = render::runBench(cases, {GetParam()}, options);
    const std::string k0 = cases[0].key(), k1 = cases[1].key();
    EXPECT_EQ(sequential, (std::vector<std::string>{k0 + " 0", k0 + " 1", k0 + " 2", k1 + " 0",
                                                    k1 + " 1", k1 + " 2"}));
    EXPECT_EQ(interleaved, (std::vector<std::string>{k0 + " 0", k1 + " 0", k0 + " 1", k1 + " 1",
                                                     k0 + " 2", k1 + " 2"}));
    EXPECT_TRUE(b["options"]["interleave"].get<bool>());
    EXPECT_EQ(b["backends"][0]["validationErrors"], 0u);
    ASSERT_EQ(a["results"].size(), 2u);
    ASSERT_EQ(b["results"].size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        SCOPED_TRACE(cases[i].key());
        ASSERT_FALSE(b["results"][i].contains("refused")) << b["results"][i]["refused"];
        EXPECT_EQ(b["results"][i]["key"], a["results"][i]["key"]);
        EXPECT_EQ(b["results"][i]["cpuFrameMs"]["samples"], 2u);
        EXPECT_EQ(b["results"][i]["gpuPassMs"].size(), a["results"][i]["gpuPassMs"].size());
        EXPECT_EQ(b["results"][i]["error"], a["results"][i]["error"]);
        EXPECT_EQ(b["results"][i]["memory"], a["results"][i]["memory"]);
    }
}

TEST(BenchSweep, QuickSweepCoversEveryTechniqueAndBadFilesAreRefused) {
    const auto cases = render::quickSweep();
    for (const render::TechniqueInfo& t : render::techniques()) {
        size_t n = 0;
        for (const auto& c : cases) n += c.settings.technique == t.name;
        EXPECT_GE(n, 2u) << t.name;
    }
    std::set<std::string> keys;
    for (const auto& c : cases)
        EXPECT_TRUE(keys.insert(c.key()).second) << "duplicate key " << c.key();
    auto error = [](const char* text) {
        try {
            render::sweepFromJson(gdi::Json::parse(text));
        } catch (const gdi::Error& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    EXPECT_EQ(error(R"({"cases": [{"technique": "forward", "colour": 1}]})"),
              "sweep: unknown key \"colour\" in a case");
    EXPECT_EQ(error(R"({"cases": [{"msaa": 16}]})"),
              "sweep: \"msaa\" must be an integer in [1, 8], got 16");
    EXPECT_EQ(error(R"({"cases": [{"size": "big"}]})"), "sweep: \"size\" must be WxH, got big");
    EXPECT_EQ(error(R"({"cases": []})"), "sweep: no cases");
    EXPECT_EQ(error(R"([1, 2])"), "sweep: expected an object with a \"cases\" array");
    EXPECT_NE(error(R"({"cases": [{"technique": "raytrace"}]})").find("valid: forward"),
              std::string::npos);
    EXPECT_EQ(error(R"({"cases": [{"technique": "redeferred", "msaa": 4}]})"),
              "sweep: case spheres/redeferred/msaa4/96x72: redeferred takes no --msaa");
    EXPECT_EQ(
        error(R"({"cases": [{"technique": "forward-plus", "clusterDepthBounds": false}]})"),
        "sweep: case spheres/forward-plus/no-cluster-bounds/96x72: forward-plus reads no cluster grid (--no-cluster-bounds)");
    EXPECT_EQ(
        error(R"({"cases": [{"technique": "redeferred", "brdf": "gltf"}]})"),
        "sweep: case spheres/redeferred/brdf-gltf/96x72: redeferred shades with the separable BRDF only (--brdf)");
    EXPECT_EQ(error(R"({"cases": [{"brdf": "phong"}]})"),
              "sweep: \"brdf\" must be auto, gltf or separable, got \"phong\"");
    EXPECT_EQ(render::sweepFromJson(gdi::Json::parse(
                  R"({"cases": [{"technique": "deferred", "brdf": "separable"}]})"))[0]
                  .key(),
              "spheres/deferred/brdf-separable/96x72");
    EXPECT_EQ(error(R"({"cases": [{"technique": "forward"}, {"technique": "forward"}]})"),
              "sweep: case spheres/forward/96x72 is listed twice");
    EXPECT_EQ(error(R"({"cases": [{"lights": []}]})"), "sweep: \"lights\" lists no values");
    EXPECT_EQ(error(R"({"cases": [], "frames": 3})"), "sweep: unknown top-level key \"frames\"");
}

// Arrays (and "technique": "all") expand to every combination; options a technique does not take
// are skipped in a matrix, not benched as the default.
TEST(BenchSweep, MatrixExpands) {
    const auto cases = render::sweepFromJson(gdi::Json::parse(R"({"cases": [
        {"scene": "builtin:lights", "lights": [8, 64], "technique": "all", "illumScale": [1, 2]}]})"));
    size_t withIBuffer = 0;
    for (const auto& t : render::techniques()) withIBuffer += t.illumScale;
    ASSERT_EQ(cases.size(), 2 * (render::techniques().size() + withIBuffer));
    EXPECT_EQ(cases[0].key(), "lights8/" + std::string(render::techniques()[0].name) + "/96x72");
    EXPECT_EQ(cases.back().key(),
              "lights64/" + std::string(render::techniques().back().name) + "/scale2/96x72");
    for (const auto& c : cases) {
        EXPECT_TRUE(c.settings.illumScale == 1 ||
                    render::findTechnique(c.settings.technique).illumScale)
            << c.key();
        EXPECT_TRUE(c.lights == 8 || c.lights == 64);
    }
}

// The documented sweeps (bench/sweeps/, run by tools/bench/regenerate-benchmarks.sh) parse: a
// renamed technique or option must fail here, not an hour into a full sweep.
TEST(BenchSweep, DocumentedSweepsParse) {
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(FE_SWEEPS_DIR)) {
        if (entry.path().extension() != ".json") continue;
        ++files;
        std::ifstream f(entry.path());
        const gdi::Json sweep = gdi::Json::parse(f);
        EXPECT_TRUE(sweep.contains("description")) << entry.path();
        // Every case object expands to at least one measurement (a list option to several).
        ASSERT_TRUE(sweep.contains("cases")) << entry.path();
        EXPECT_GE(render::sweepFromJson(sweep).size(), sweep["cases"].size()) << entry.path();
        EXPECT_GT(sweep["cases"].size(), 0u) << entry.path();
    }
    EXPECT_GE(files, 3u);
}
