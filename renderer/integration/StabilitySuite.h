// Layer 8 (Integration): the stability suite's cases, shared by its test (ctest -L stability)
// and the bench's report (fe bench --stability): where rendering methods fail. Each case either
// renders every pixel finite, its error within a stated bound of the CPU reference, or is
// refused with a message naming the problem.
#pragma once
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "assets/Scene.h"
#include "fe/gdi/Device.h"

namespace fe::render {

struct StabilityCase {
    std::string name;
    std::function<assets::Scene()>
        scene;  // built without finalizeScene's checks where it must be broken
    // Bound on the percentage of pixels beyond 5/255 of the reference for the exact techniques
    // (negative: not compared).
    double exactBound = 1.0;
    std::string refusal;  // non-empty: every technique must refuse with a message containing it
    // The case renders at the suite's size divided by this: where every tile's light list
    // overflows (65536 lights), each pixel walks every light, and at the full size that one case
    // cost more than all the others together (at a third, 16x12, still two thirds of the suite's
    // time; at a sixth, 8x6, it is one partial tile, which overflows just the same).
    uint32_t sizeDivisor = 1;
    uint32_t width(uint32_t suiteWidth) const { return std::max(1u, suiteWidth / sizeDivisor); }
    uint32_t height(uint32_t suiteHeight) const { return std::max(1u, suiteHeight / sizeDivisor); }
};

// Roughness below the clamp, grazing angles, lights at the eye, inside geometry, at the range
// boundary, of 1e4 and 1e7 cd, none, one, 4096 and 65536 of them, a scene 1e5 from the origin,
// denormal data, degenerate triangles, translucent materials; NaN and infinite data (refused).
std::vector<StabilityCase> stabilityCases();
// The cases whose name contains one of the comma-separated parts of `names` (empty: all); a
// part that names no case throws gdi::Error listing the cases.
std::vector<StabilityCase> stabilityCases(const std::string& names);

struct StabilityOutcome {
    bool refused = false;
    std::string message;       // the refusal
    uint32_t nonFinite = 0;    // channels that are NaN or infinite
    double percentOver5 = -1;  // against the reference (-1: not compared)
};
// Renders one case with one technique at width x height (`reference`: the case's CPU reference
// radiance, empty when not compared).
StabilityOutcome runStabilityCase(gdi::Device& device, const assets::Scene& scene,
                                  const std::string& technique, uint32_t width, uint32_t height,
                                  const std::vector<glm::dvec3>& reference);

}  // namespace fe::render
