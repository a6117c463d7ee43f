#include "render/VfxRenderer.h"

#include <cmath>
#include <cstring>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
// Binding slots of fe_particles.glsl.
constexpr uint32_t kSlotEmitters = 28, kSlotAdditive = 29, kSlotAlpha = 30, kSlotArgs = 31,
                   kSlotSorted = 32, kSlotSim = 33;
constexpr double kFrameSeconds = 1.0 / 60.0;

struct GpuEmitter {
    glm::vec4 positionRate, velocitySpread, gravityLifetime, colorStart, colorEnd, sizeSoftness;
    glm::uvec4 slots;
};
struct GpuParticle {
    glm::vec4 positionSize, color, depth;
};
static_assert(sizeof(GpuEmitter) == 112 && sizeof(GpuParticle) == 48,
              "std430 layouts of fe_particles.glsl");

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::vec4& v) { return finite(glm::vec3(v)) && std::isfinite(v.w); }
}  // namespace

VfxRenderer::VfxRenderer(TechniqueContext& ctx,
                         const std::vector<assets::ParticleEmitter>& emitters)
    : objects_(ctx.device), ctx_(ctx), emitters_(emitters) {
    gdi::Device& d = ctx.device;
    std::vector<GpuEmitter> gpu;
    uint32_t alphaSlots = 0;
    double longest = 0.0;
    for (const assets::ParticleEmitter& e : emitters) {
        const std::string what = "particle emitter '" + e.name + "'";
        if (!finite(e.position) || !finite(e.velocity) || !finite(e.gravity) ||
            !finite(e.colorStart) || !finite(e.colorEnd) || !std::isfinite(e.spread) ||
            !std::isfinite(e.rate) || !std::isfinite(e.lifetime) || !std::isfinite(e.sizeStart) ||
            !std::isfinite(e.sizeEnd) || !std::isfinite(e.softness))
            throw gdi::Error(what + ": a value is not finite (NaN or infinity)");
        if (e.rate <= 0.0f || e.lifetime <= 0.0f || e.sizeStart < 0.0f || e.sizeEnd < 0.0f ||
            e.softness < 0.0f || e.spread < 0.0f || e.spread > 3.1416f)
            throw gdi::Error(
                what +
                ": rate and lifetime must be positive, sizes and softness not negative, spread in [0, pi]");
        if (e.maxParticles() > 1u << 20)
            throw gdi::Error(what + ": more than 2^20 particles alive at once (rate x lifetime)");
        const uint32_t n = e.maxParticles();
        gpu.push_back({glm::vec4(e.position, e.rate), glm::vec4(e.velocity, e.spread),
                       glm::vec4(e.gravity, e.lifetime), e.colorStart, e.colorEnd,
                       glm::vec4(e.sizeStart, e.sizeEnd, e.softness,
                                 e.blend == assets::ParticleEmitter::Blend::Alpha ? 1.0f : 0.0f),
                       glm::uvec4(slots_, n, 0, 0)});
        slots_ += n;
        (e.blend == assets::ParticleEmitter::Blend::Alpha ? alphaSlots : additiveSlots_) += n;
        longest = std::max(longest, double(e.lifetime));
    }
    if (alphaSlots > kMaxSortedParticles)
        throw gdi::Error("alpha-blended particles: " + std::to_string(alphaSlots) +
                         " alive at once (rate x lifetime) exceed the " +
                         std::to_string(kMaxSortedParticles) + " one work group sorts");
    time_ = longest;
    emitterBuffer_ = objects_.add(d.createBuffer({.size = gpu.size() * sizeof(GpuEmitter),
                                                  .usage = gdi::BufferUsage::Storage,
                                                  .debugName = "particle emitters"},
                                                 gdi::bytesOf(gpu)));
    auto list = [&](uint32_t n, const char* name) {
        return objects_.add(d.createBuffer({.size = std::max<uint64_t>(1, n) * sizeof(GpuParticle),
                                            .usage = gdi::BufferUsage::Storage,
                                            .debugName = name}));
    };
    additive_ = list(additiveSlots_, "particles additive");
    alpha_ = list(kMaxSortedParticles, "particles alpha");
    sorted_ = list(kMaxSortedParticles, "particles alpha sorted");
    const gdi::DrawIndirectArgs reset[2] = {{6, 0, 0, 0}, {6, 0, 0, 0}};
    args_ = objects_.add(
        d.createBuffer({.size = sizeof(reset),
                        .usage = gdi::BufferUsage::Storage | gdi::BufferUsage::Indirect |
                                 gdi::BufferUsage::CopyDst | gdi::BufferUsage::CopySrc,
                        .debugName = "particle draw arguments"}));
    argsReset_ = objects_.add(d.createBuffer({.size = sizeof(reset),
                                              .usage = gdi::BufferUsage::CopySrc,
                                              .debugName = "particle draw arguments reset"},
                                             gdi::bytesOf(reset)));
    const auto shader = [&](gdi::ShaderStage stage, const char* path) {
        return objects_.add(d.createShader({.stage = stage, .binary = shaders::find(path)}));
    };
    simulateCs_ = shader(gdi::ShaderStage::Compute, "scene/particles_simulate.comp");
    sortCs_ = shader(gdi::ShaderStage::Compute, "scene/particles_sort.comp");
    vs_ = shader(gdi::ShaderStage::Vertex, "scene/particles.vert");
    additiveFs_ = shader(gdi::ShaderStage::Fragment, "scene/particles_additive.frag");
    alphaFs_ = shader(gdi::ShaderStage::Fragment, "scene/particles_alpha.frag");
    simulate_ = objects_.add(
        d.createComputePipeline({.computeShader = simulateCs_, .debugName = "particles simulate"}));
    sort_ = objects_.add(
        d.createComputePipeline({.computeShader = sortCs_, .debugName = "particles sort"}));
    const auto draw = [&](gdi::ShaderHandle fs, gdi::BlendTargetState blend, const char* name) {
        return objects_.add(d.createGraphicsPipeline({.vertexShader = vs_,
                                                      .fragmentShader = fs,
                                                      .blend = {blend},
                                                      .colorFormats = {kRadianceFormat},
                                                      .debugName = name}));
    };
    // Additive: emitted light adds to L_o (alpha untouched); alpha: source-over.
    drawAdditive_ = draw(additiveFs_,
                         {.enable = true,
                          .srcColor = gdi::BlendFactor::One,
                          .dstColor = gdi::BlendFactor::One,
                          .srcAlpha = gdi::BlendFactor::Zero,
                          .dstAlpha = gdi::BlendFactor::One},
                         "particles additive");
    drawAlpha_ = draw(alphaFs_,
                      {.enable = true,
                       .srcColor = gdi::BlendFactor::SrcAlpha,
                       .dstColor = gdi::BlendFactor::OneMinusSrcAlpha,
                       .srcAlpha = gdi::BlendFactor::Zero,
                       .dstAlpha = gdi::BlendFactor::One},
                      "particles alpha");
}

// Four graph passes, so the graph orders the buffers between them with buffer barriers (the
// backend's automatic barriers stay off): reset the draw arguments, simulate, sort, draw.
void VfxRenderer::declare(graph::RenderGraph& g, graph::TextureId output, graph::TextureId depth) {
    using A = gdi::BufferAccess;
    const auto list = [&](const char* name, gdi::BufferHandle b, uint64_t particles) {
        return g.importBuffer(name, b, std::max<uint64_t>(1, particles) * sizeof(GpuParticle));
    };
    const graph::BufferId emitters =
        g.importBuffer("particle emitters", emitterBuffer_, emitters_.size() * sizeof(GpuEmitter));
    const graph::BufferId additive = list("particles additive", additive_, additiveSlots_);
    const graph::BufferId alpha = list("particles alpha", alpha_, kMaxSortedParticles);
    const graph::BufferId sorted = list("particles alpha sorted", sorted_, kMaxSortedParticles);
    const graph::BufferId args =
        g.importBuffer("particle draw arguments", args_, 2 * sizeof(gdi::DrawIndirectArgs));
    const graph::BufferId argsReset = g.importBuffer("particle draw arguments reset", argsReset_,
                                                     2 * sizeof(gdi::DrawIndirectArgs));
    g.markOutput(args);  // lastCounts() reads it back

    g.addPass(
        "particles reset",
        [&](graph::PassBuilder& b) {
            b.buffer(argsReset, A::CopySrc);
            b.buffer(args, A::CopyDst);
            // Reset, simulation and sort share nothing with the scene's passes: on the compute
            // queue beside them (RenderSettings::asyncCompute), until the particles are drawn.
            if (ctx_.settings.asyncCompute) b.asyncCompute();
        },
        [this](graph::PassContext& pc) {
            pc.cmd.copyBuffer(args_, 0, argsReset_, 0, sizeof(gdi::DrawIndirectArgs) * 2);
        });

    g.addPass(
        "particles simulate",
        [&](graph::PassBuilder& b) {
            b.buffer(emitters, A::StorageRead);
            b.buffer(additive, A::StorageWrite);
            b.buffer(alpha, A::StorageWrite);
            b.buffer(args, A::StorageRead | A::StorageWrite);  // atomic appends count the instances
            if (ctx_.settings.asyncCompute) b.asyncCompute();
        },
        [this](graph::PassContext& pc) {
            gdi::CommandList& cmd = pc.cmd;
            // Every light, the shadowed ones too (particles receive no shadows), as the transparent pass.
            FrameConstants fc = ctx_.frame;
            fc.lightRange = glm::uvec4(0, ctx_.scene.lightCount(), 0, 0);
            frame_ = ctx_.queue.upload(fc);
            const glm::vec4 sim(float(time_), float(emitters_.size()), float(slots_), 0.0f);
            const UploadAllocation simulation = ctx_.queue.upload(sim);
            time_ += kFrameSeconds;
            cmd.setPipeline(simulate_);
            cmd.setUniformBuffer(kSlotFrame, frame_.buffer, frame_.offset, frame_.size);
            cmd.setStorageBuffer(kSlotLights, ctx_.scene.lightBuffer());
            cmd.setUniformBuffer(kSlotSim, simulation.buffer, simulation.offset, simulation.size);
            cmd.setStorageBuffer(kSlotEmitters, emitterBuffer_);
            cmd.setStorageBuffer(kSlotAdditive, additive_);
            cmd.setStorageBuffer(kSlotAlpha, alpha_);
            cmd.setStorageBuffer(kSlotArgs, args_);
            cmd.dispatch((slots_ + 63) / 64);
        });

    g.addPass(
        "particles sort",
        [&](graph::PassBuilder& b) {
            b.buffer(alpha, A::StorageRead);
            b.buffer(sorted, A::StorageWrite);
            b.buffer(args,
                     A::StorageRead | A::StorageWrite);  // caps the alpha count at the list size
            if (ctx_.settings.asyncCompute) b.asyncCompute();
        },
        [this](graph::PassContext& pc) {
            gdi::CommandList& cmd = pc.cmd;
            cmd.setPipeline(sort_);
            cmd.setStorageBuffer(kSlotAlpha, alpha_);
            cmd.setStorageBuffer(kSlotSorted, sorted_);
            cmd.setStorageBuffer(kSlotArgs, args_);
            cmd.dispatch(1);
        });

    g.addPass(
        "particles",
        [&](graph::PassBuilder& b) {
            b.sample(depth);
            b.colorTarget(output, gdi::LoadOp::Load);
            b.buffer(sorted, A::StorageRead);
            b.buffer(additive, A::StorageRead);
            b.buffer(args, A::Indirect);
        },
        [this, depth](graph::PassContext& pc) {
            gdi::CommandList& cmd = pc.cmd;
            pc.beginRenderPass();
            for (const auto& [pipeline, list, offset] :
                 {std::tuple{drawAlpha_, sorted_, sizeof(gdi::DrawIndirectArgs)},
                  std::tuple{drawAdditive_, additive_, size_t(0)}}) {
                cmd.setPipeline(pipeline);
                cmd.setUniformBuffer(kSlotFrame, frame_.buffer, frame_.offset, frame_.size);
                cmd.setStorageBuffer(kSlotSorted, list);
                cmd.setTexture(kSlotDepth, pc.texture(depth), ctx_.pointSampler);
                cmd.drawIndirect(args_, offset);
            }
            cmd.endRenderPass();
        });
}

VfxRenderer::Counts VfxRenderer::lastCounts() {
    ctx_.device.waitIdle();
    const std::vector<uint8_t> bytes =
        ctx_.device.readBuffer(args_, 0, sizeof(gdi::DrawIndirectArgs) * 2);
    gdi::DrawIndirectArgs a[2];
    std::memcpy(a, bytes.data(), sizeof(a));
    return {a[0].instanceCount, a[1].instanceCount};
}

std::vector<float> VfxRenderer::lastAlphaDistances() {
    const uint32_t n = lastCounts().alpha;
    std::vector<float> out;
    if (n == 0) return out;
    const std::vector<uint8_t> bytes =
        ctx_.device.readBuffer(sorted_, 0, uint64_t(n) * sizeof(GpuParticle));
    for (uint32_t i = 0; i < n; ++i) {
        GpuParticle p;
        std::memcpy(&p, bytes.data() + i * sizeof(GpuParticle), sizeof(p));
        out.push_back(p.depth.x);
    }
    return out;
}

VfxRenderer::Counts VfxRenderer::aliveAt(const std::vector<assets::ParticleEmitter>& emitters,
                                         double seconds) {
    Counts c;
    for (const assets::ParticleEmitter& e : emitters) {
        const uint32_t n = e.maxParticles();
        const double period = double(n) / e.rate;
        for (uint32_t i = 0; i < n; ++i) {
            const double since = seconds - double(i) / e.rate;
            if (since < 0.0) continue;
            const double age = since - std::floor(since / period) * period;
            if (age < e.lifetime)
                (e.blend == assets::ParticleEmitter::Blend::Alpha ? c.alpha : c.additive) += 1;
        }
    }
    return c;
}

}  // namespace fe::render
