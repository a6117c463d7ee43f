#include "PostShader.h"

#include <chrono>
#include <fstream>
#include <iterator>
#include <regex>

#include "fe/gdi/ShaderRegistry.h"

namespace fe::tools {

PostShader::PostShader(gdi::Device& device, std::string path)
    : device_(device), path_(std::move(path)), objects_(device) {
    vs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/fullscreen.vert")}));
    sampler_ = objects_.add(device.createSampler({.minFilter = gdi::Filter::Nearest,
                                                  .magFilter = gdi::Filter::Nearest,
                                                  .addressU = gdi::AddressMode::ClampToEdge,
                                                  .addressV = gdi::AddressMode::ClampToEdge}));
}

PostShader::~PostShader() {
    for (gdi::PipelineHandle p : {pipeline_})
        if (p) device_.destroy(p);
    if (fs_) device_.destroy(fs_);
    if (target_) device_.destroy(target_);
    if (source_) device_.destroy(source_);
}

std::optional<std::string> PostShader::refresh() {
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(path_, ec);
    const uintmax_t size = ec ? 0 : std::filesystem::file_size(path_, ec);
    if (ec) {
        if (seenTime_ || seenSize_ == uintmax_t(-1)) return std::nullopt;  // said once
        seenSize_ = uintmax_t(-1);
        return "cannot read it (" + ec.message() + ")";
    }
    if (seenTime_ && *seenTime_ == time && seenSize_ == size) return std::nullopt;
    // A file written in place is truncated, then written: read only once its time and size have
    // held for 50 ms, or a look between the two compiles an empty file (and says so).
    const auto now = std::chrono::steady_clock::now();
    if (!(pendingTime_ == time && pendingSize_ == size)) {
        pendingTime_ = time, pendingSize_ = size, pendingSince_ = now;
        return std::nullopt;
    }
    if (now - pendingSince_ < std::chrono::milliseconds(50)) return std::nullopt;
    seenTime_ = time, seenSize_ = size;
    std::ifstream in(path_, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const bool hlsl = path_.size() > 5 && path_.substr(path_.size() - 5) == ".hlsl";
    std::smatch entry;  // HLSL: main, or the function a "// fe-entry: NAME" line names
    const std::string entryPoint =
        hlsl && std::regex_search(text, entry, std::regex("// fe-entry: ([A-Za-z_0-9]+)"))
            ? entry[1].str()
            : "main";
    try {
        const gdi::ShaderHandle fs = device_.createShader(
            {.stage = gdi::ShaderStage::Fragment,
             .entryPoint = entryPoint.c_str(),
             .source = {.text = text,
                        .language = hlsl ? gdi::ShaderLanguage::HLSL : gdi::ShaderLanguage::GLSL,
                        .name = path_.c_str()}});
        const gdi::ShaderHandle previous = fs_;
        fs_ = fs;
        try {
            makePipeline();
        } catch (...) {
            fs_ = previous;
            device_.destroy(fs);
            throw;
        }
        if (previous) device_.destroy(previous);
        return "compiled";
    } catch (const gdi::Error& e) {
        return std::string(e.what()) + (pipeline_ ? "; the previous version stays" : "");
    }
}

void PostShader::makePipeline() {
    if (!fs_ || format_ == gdi::Format::Undefined) return;
    const gdi::PipelineHandle p = device_.createGraphicsPipeline(
        {.vertexShader = vs_,
         .fragmentShader = fs_,
         .colorFormats = {format_},
         .bindings = {{0, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment}},
         .debugName = "fe view post shader"});
    if (pipeline_) device_.destroy(pipeline_);
    pipeline_ = p;
}

gdi::TextureHandle PostShader::apply(gdi::TextureHandle input) {
    const gdi::TextureDesc d = device_.desc(input);
    if (d.format != format_) {
        format_ = d.format;
        if (pipeline_) device_.destroy(pipeline_), pipeline_ = {};
        if (fs_) makePipeline();
    }
    if (!pipeline_) return input;
    // `t` as a texture of the input's size and format with this usage, made anew when it is not.
    auto sized = [&](gdi::TextureHandle& t, gdi::TextureUsage usage, const char* name) {
        if (t && device_.desc(t).width == d.width && device_.desc(t).height == d.height &&
            device_.desc(t).format == d.format)
            return;
        if (t) device_.destroy(t);
        t = device_.createTexture({.format = d.format,
                                   .width = d.width,
                                   .height = d.height,
                                   .usage = usage,
                                   .debugName = name});
    };
    sized(target_,
          gdi::TextureUsage::RenderTarget | gdi::TextureUsage::Sampled |
              gdi::TextureUsage::CopySrc | gdi::TextureUsage::CopyDst,
          "fe view post shader output");
    auto cmd = device_.createCommandList();
    gdi::TextureHandle sampled = input;
    if (!any(d.usage, gdi::TextureUsage::Sampled)) {  // a display texture: copied to be read
        sized(source_, gdi::TextureUsage::Sampled | gdi::TextureUsage::CopyDst,
              "fe view post shader input");
        cmd->copyTexture(source_, input);
        sampled = source_;
    }
    cmd->beginRenderPass({.colors = {{.texture = target_}}});
    cmd->setPipeline(pipeline_);
    cmd->setTexture(0, sampled, sampler_);
    cmd->draw(3);
    cmd->endRenderPass();
    device_.submit(*cmd);
    return target_;
}

}  // namespace fe::tools
