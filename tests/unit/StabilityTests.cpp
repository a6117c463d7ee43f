// The stability suite (ctest label "stability"; the cases: integration/StabilitySuite.h), on
// every backend with every technique. A case either renders every pixel finite with its error
// within the stated bound, or is refused with a clear message that the test checks. The table
// it prints (technique x case: percentage of pixels beyond 5/255 of the CPU reference, or the
// refusal) is the suite's result (docs/BENCHMARKS.md, fe bench --stability).
#include <gtest/gtest.h>

#include <cstdlib>
#include <iomanip>
#include <map>
#include <sstream>

#include "BackendTest.h"
#include "integration/StabilitySuite.h"
#include "reference/CpuReference.h"
#include "render/ForwardMultipassRenderer.h"
#include "render/TechniqueRenderer.h"

using namespace fe;

namespace {
constexpr uint32_t kW = 48, kH = 36;
class Stability : public fe::testing::BackendTest {
protected:
    Stability() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};
}  // namespace

TEST_P(Stability, EveryCaseRendersFiniteWithinItsBoundOrIsRefused) {
    std::map<std::string, std::map<std::string, std::string>>
        table;  // case -> technique -> outcome
    // FE_STABILITY_CASES (fe bench --stability-cases' syntax) runs some of them: the sanitized
    // suite takes the broken-data cases (tools/run-sanitized-tests.sh).
    const char* only = std::getenv("FE_STABILITY_CASES");
    for (const render::StabilityCase& c : render::stabilityCases(only ? only : "")) {
        const assets::Scene scene = c.scene();
        std::map<bool, std::vector<glm::dvec3>> references;  // separable BRDF -> the exact image
        for (const render::TechniqueInfo& t : render::techniques()) {
            if (std::string(t.name).find("tiled") != std::string::npos &&
                !device->info().features.computeShaders)
                continue;
            std::vector<glm::dvec3>& reference = references[t.separableBrdf];
            if (reference.empty() && c.refusal.empty() && c.exactBound >= 0.0)
                reference = render::renderReference(scene, *scene.camera, c.width(kW), c.height(kH),
                                                    {.brdf = t.defaultBrdf()})
                                .radiance;
            SCOPED_TRACE(c.name + ", " + t.name);
            const render::StabilityOutcome o = render::runStabilityCase(
                *device, scene, t.name, c.width(kW), c.height(kH), reference);
            std::string outcome;
            if (o.refused) {
                outcome = "refused: " + o.message;
                const bool manyLights =
                    scene.lights.size() > render::ForwardMultipassRenderer::kMaxLights &&
                    std::string(t.name) == "forward-multipass";
                if (manyLights) {
                    EXPECT_NE(o.message.find("forward-multipass draws the scene once per light"),
                              std::string::npos)
                        << o.message;
                } else {
                    EXPECT_FALSE(c.refusal.empty()) << "unexpected refusal: " << o.message;
                    EXPECT_NE(o.message.find(c.refusal), std::string::npos) << o.message;
                }
            } else {
                EXPECT_EQ(o.nonFinite, 0u);
                EXPECT_TRUE(c.refusal.empty()) << "expected a refusal: " << c.refusal;
                if (o.percentOver5 >= 0.0) {
                    std::ostringstream s;
                    s << std::fixed << std::setprecision(2) << o.percentOver5 << " %";
                    outcome = s.str();
                    // The exact techniques within the case's bound; the light pre-pass (its
                    // monochrome specular) is measured, not bounded.
                    if (std::string(t.name).find("light-prepass") == std::string::npos) {
                        EXPECT_LE(o.percentOver5, c.exactBound);
                    }
                } else {
                    outcome = o.nonFinite ? "NON-FINITE" : "finite";
                }
            }
            table[c.name][t.name] = outcome;
        }
    }
    std::ostringstream o;
    o << "stability table (" << GetParam()
      << "): % of pixels beyond 5/255 of the reference, or the outcome\n";
    for (const auto& [name, row] : table) {
        o << "  " << name << ":";
        for (const auto& [t, outcome] : row) o << " " << t << " " << outcome.substr(0, 60) << ";";
        o << "\n";
    }
    std::cout << o.str();
    RecordProperty("table", o.str());
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(Stability);
