// fe view --post-shader FILE: a fragment shader over the displayed image, compiled from its file
// (GLSL 450, or HLSL when the name ends in .hlsl) and compiled again each time the file changes,
// as a shader editor's hot reload does; a file that does not compile leaves the last good shader
// in place and says why. The shader's interface: the image at binding 0 (GLSL `uniform
// sampler2D frame`; HLSL `Texture2D frame : register(t0)` with a sampler at s0), one colour
// output, gl_FragCoord / SV_Position in the image's pixels.
#pragma once
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"

namespace fe::tools {

class PostShader {
public:
    PostShader(gdi::Device& device, std::string path);
    ~PostShader();
    PostShader(const PostShader&) = delete;
    PostShader& operator=(const PostShader&) = delete;
    // Compiles the file again when it changed since the last look (time or size) and has held
    // still for 50 ms; returns what happened then ("compiled", or the error while the previous
    // shader stays), else nothing.
    std::optional<std::string> refresh();
    // `input` through the shader into a texture of its size and format; `input` itself while no
    // version of the file has compiled.
    gdi::TextureHandle apply(gdi::TextureHandle input);

private:
    void makePipeline();
    gdi::Device& device_;
    std::string path_;
    gdi::DeviceObjects objects_;
    std::optional<std::filesystem::file_time_type> seenTime_;
    uintmax_t seenSize_ = 0;
    // The file's time and size as last seen changing, and since when (refresh waits for them to settle).
    std::optional<std::filesystem::file_time_type> pendingTime_;
    uintmax_t pendingSize_ = 0;
    std::chrono::steady_clock::time_point pendingSince_;
    gdi::ShaderHandle vs_, fs_;
    gdi::SamplerHandle sampler_;
    gdi::PipelineHandle pipeline_;
    gdi::Format format_ = gdi::Format::Undefined;  // the pipeline's target format
    gdi::TextureHandle target_, source_;  // output; the input copied when it cannot be sampled
};

}  // namespace fe::tools
