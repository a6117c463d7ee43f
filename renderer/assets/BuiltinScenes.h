// Layer 5 (Communication: Asset Loader): procedural scenes that need no files, for demos,
// benchmarks and tests, and the "builtin:NAME or file path" entry point.
//
// "spheres": a grid x grid (default 7 x 7) of UV spheres (radius 0.4, spacing 1, z = 0), one
//   mesh + material per sphere. Roughness goes 0..1 left to right (columns), metallic 0..1 top to
//   bottom (rows); base colour linear (0.9, 0.3, 0.1). Lights: directional key (white, 2 lux,
//   travelling normalize(0.5, -0.6, -1)), directional fill ((0.8, 0.9, 1), 0.5 lux, travelling
//   normalize(-0.6, -0.2, -1)), point (white, 30 cd, at (2, 3, 4), infinite range). Camera on +Z
//   looking along -Z, yfov 45 degrees, at z = 0.4 + 1.1 * (half grid extent + 0.4) / tan(22.5 deg)
//   (the sphere fronts fit with a 10% margin), near 0.1, far 100.
//
// "lights": EXACTLY 121 cubes [-1, 1]^3 (one shared mesh, 24 vertices / 36 indices) in an
//   11 x 11 grid with spacing 3 in the z = 0 plane: centres (x, y, 0), x, y in {-15, -12, ..., 15};
//   one material: base colour 0.8 grey, metallic 0, roughness 0.5. Camera at (0, 0, -15)
//   looking along +Z, up +Y, yfov 60 degrees, near 0.1, far 100. BuiltinOptions::lights point
//   lights (default 512) of range 2 (see lightsSceneLights()).
//
// "plane": analytic checks. A 2 x 2 quad in z = 0 facing +Z (base colour 0.5 grey, metallic 0,
//   roughness 0.5), a point light at (0, 0, 1) of 1 cd, infinite range (so E = 1 lux at the
//   centre), camera at (0, 0, 3) looking along -Z, yfov 45 degrees, near 0.1, far 100.
//
// "triangle": the smallest scene: one triangle (-1,-1,0), (1,-1,0), (0,1,0) facing +Z (white,
//   metallic 0, roughness 1), one directional light travelling along -Z at 1 lux, the "plane"
//   camera.
//
// "shadows": shadow casting under every kind of light. A 10 x 10 ground quad in y = 0 facing +Y
//   (grey 0.5, roughness 0.7), a gold metal sphere (radius 0.6 at (-1.3, 0.6, 0.2), roughness
//   0.3), a red cube (half size 0.45 at (1.1, 0.45, -0.4), turned 30 degrees about Y) and a thin
//   white pole (0.12 x 2 x 0.12 at (0.2, 1, 1.3)). Lights: a sun (directional, 2.5 lux, warm,
//   travelling normalize(-0.5, -1, -0.35)), a spot (60 cd at (2.6, 3.2, 2.4) aimed at the origin,
//   cone 20/30 degrees) and a lamp (point, 6 cd, orange, at (-2.4, 1.6, 1.8)), none with a range.
//   Camera at (0, 3, 6) looking at (0, 1.4, 0) (sky above the ground), yfov 45 degrees,
//   near 0.1, far 100.
//
// "atrium": a deep two-storey arcade standing in for Sponza (whose geometry cannot be had here).
//   A hall 12 m wide (x in [-6, 6]), 8 m high and 60 m long (z from 0 to -60): stone floor,
//   plaster side and end walls (boxes 0.2 m thick). Along each side at x = +-3.5, a column every
//   4 m (0.6 m square, up to the beam at 3.45 m), a marble beam along the arcade, a stone gallery
//   floor (x from 3.5 to 6, at 4 m) and slimmer upper columns to the ceiling height. With
//   BuiltinOptions::hangings, translucent banners (alpha 0.55, red and blue, double-sided,
//   3.2 x 2.4 m) hang facing the axis between the upper columns every other bay. Lights:
//   BuiltinOptions::lights point lights (atriumLights()). Camera at (0, 1.7, 1.5) looking down
//   the hall (along -z, slightly down), yfov 60 degrees, near 0.1, far 100. Boxes and quads only.
// "crowd": BuiltinOptions::crowd reeds (tapered tubes 2 m tall, radius 0.08 m, 33 rings of 17
//   vertices) in a square grid 0.5 m apart on a soil ground (y = 0), one shared mesh each reed
//   drawn through a skin of its own (a chain of 4 joints 0.5 m apart, every vertex blended
//   linearly between the two joints around its height) and a morph target (a bulge fattest
//   halfway up). Its animation "sway" (2 s, LINEAR) bends each joint about Z and X and breathes
//   the bulge, each reed out of phase: the mesh deformation's stress case (docs/BENCHMARKS.md).
//   Lights: a directional sun (2.5 lux) and a point fill (8 cd at (0, 4, 3)). Camera in front,
//   above, looking down the grid, yfov 50 degrees, near 0.1, far 200.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "assets/AssetError.h"
#include "assets/GltfLoader.h"
#include "assets/Scene.h"

namespace fe::assets {

struct BuiltinOptions {
    uint32_t lights = 512;    // "lights": number of point lights
    uint32_t frame = 0;       // "lights": animation frame (light positions)
    uint32_t sphereGrid = 7;  // "spheres": spheres per row and column (2..16)
    bool hangings = true;     // "atrium": the translucent banners
    uint32_t crowd = 64;      // "crowd": the number of reeds
};

// The "atrium" scene's point lights: light i at a fixed-seed hash position uniform in the hall
// (x in [-5.5, 5.5], y in [0.3, 7.5], z in [-58, -1]), a hue from the same hash (saturation 0.6),
// 3 cd, range 2.5 m.
std::vector<Light> atriumLights(uint32_t count);

const std::vector<std::string>& builtinSceneNames();

// Throws AssetError listing the valid names when `name` is unknown.
Scene makeBuiltinScene(std::string_view name, const BuiltinOptions& options = {});

// The point lights of the "lights" scene for a frame, so a renderer can animate them without
// rebuilding the scene. Light i is a pure function of (i, frame):
//   a fixed-seed hash of i gives a centre (cx, cy) uniform in [-14, 14]^2, a height z uniform in
//   [-2, 2], a phase p in [0, 2 pi), an angular speed w = +-(0.5..1.5) * 2 pi / 600 rad per frame
//   and a hue h in [0, 1);
//   position = (cx + cos(p + w * frame), cy + sin(p + w * frame), z): a unit-radius orbit, so
//   x, y stay in [-15, 15] and z in [-2, 2] for every frame (one loop every 300-1200 frames);
//   colour = HSV(h, 0.7, 1) (average luminance about 0.66), range 2, intensity 4 cd. With
//   512 lights the lit faces facing the camera average about 0.3 linear radiance (exposure 1),
//   about 10% of them above 0.8, about a fifth unlit: bright pools of light, little clipping.
std::vector<Light> lightsSceneLights(uint32_t count, uint32_t frame);

// "builtin:NAME" -> makeBuiltinScene(NAME, builtin); anything else is a glTF file path.
Scene loadScene(std::string_view spec, const LoadOptions& load = {},
                const BuiltinOptions& builtin = {});

}  // namespace fe::assets
