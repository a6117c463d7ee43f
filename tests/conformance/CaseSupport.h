// Helpers shared by the conformance case files: expected images, exact comparisons, a
// full-screen pass that samples one texture, and error checks.
//
// A case owns what it creates through a gdi::DeviceObjects (one per case, or per loop
// iteration for objects remade each time) instead of destroying it at its end, so a case that
// throws half-way (a failed check, an out-of-memory error, a lost device) leaves nothing behind.
#pragma once
#include <array>
#include <functional>
#include <string>

#include "Conformance.h"
#include "fe/gdi/DeviceObjects.h"

namespace fe::conformance {

constexpr uint32_t kCaseSize = 64;  // every rendered case image is 64x64
using Texel = std::array<float, 4>;

gdi::Image solid(gdi::Format f, Texel c, uint32_t w = kCaseSize, uint32_t h = kCaseSize);
// A 64x64 image whose texel (x, y) is fn(x, y).
gdi::Image expectImage(gdi::Format f, const std::function<Texel(uint32_t, uint32_t)>& fn,
                       uint32_t w = kCaseSize, uint32_t h = kCaseSize);
// Expected to match exactly (data written and read back, or values exact in the format).
CaseImage exact(const std::string& name, gdi::Image image, gdi::Image expected);
// Expected within absTolerance on every pixel, for the reason given (the report shows it).
CaseImage within(const std::string& name, gdi::Image image, gdi::Image expected,
                 double absTolerance, std::string reason);
// A shader from the registry (fe::shaders::find), owned by `o`.
gdi::ShaderHandle registryShader(gdi::DeviceObjects& o, gdi::ShaderStage stage, const char* path);
// A 64x64 render target that can be read back, owned by `o`.
gdi::TextureHandle caseTarget(gdi::DeviceObjects& o, gdi::Format f = gdi::Format::RGBA8);
// Within `steps` steps of float-to-unorm rounding: values drawn into an 8-bit target.
CaseImage drawn8(const std::string& name, gdi::Image image, gdi::Image expected,
                 double steps = 1.0);
// True when fn throws gdi::Error (the device's clear error for bad input).
bool throws(const std::function<void()>& fn);
// Messages that must be the same gdi::Error on every backend: fn throws one containing `text`.
void expectError(const std::function<void()>& fn, const std::string& text);

// The 128-byte block of constants_quad.vert/.frag.
struct QuadConstants {
    float rect[4];  // x0, y0, x1, y1 in clip space
    float color[4];
    float unused[20];
    float tail[4];  // added to the colour: proves the last bytes arrive
};
static_assert(sizeof(QuadConstants) == gdi::kMaxConstantBytes);
// A quad of constants_quad.vert covering pixels [x0, x1) x [y0, y1) of the 64x64 target.
QuadConstants pixelQuad(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1,
                        Texel color = {1, 1, 1, 1});

// fullscreen_ubo.vert + a fragment shader with a uniform block at slot 0 (vec4 a, vec4 b; the
// triangle's depth is b.x) and a sampled texture at slot 1, drawn into a new 64x64 target.
struct FullscreenSampler {
    gdi::DeviceObjects objects;
    gdi::ShaderHandle vs, fs;
    gdi::SamplerHandle sampler;
    std::string fragment;
    FullscreenSampler(gdi::Device& d, const char* fragmentShader,
                      const gdi::SamplerDesc& samplerDesc = {
                          .minFilter = gdi::Filter::Nearest,
                          .magFilter = gdi::Filter::Nearest,
                          .addressU = gdi::AddressMode::ClampToEdge,
                          .addressV = gdi::AddressMode::ClampToEdge,
                          .addressW = gdi::AddressMode::ClampToEdge});
    gdi::Image draw(gdi::Device& d, gdi::TextureHandle texture, gdi::Format target,
                    std::array<float, 4> a = {}, std::array<float, 4> b = {});
};

}  // namespace fe::conformance
