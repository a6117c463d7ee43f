// Cost of the abstraction: CPU time to record and submit 10,000 small draws through
// gdi::CommandList, against the same draws issued with direct Vulkan and direct GL calls on
// the very same objects (pipeline, buffers, render target, command buffer; found through
// Device::nativeObject and CommandList::nativeCommandBuffer). The once-per-frame work around
// the draws goes through the backend on both sides.
//
// Each draw binds its own 64-byte slice of a uniform buffer and draws one small triangle,
// the typical per-object pattern. GPU execution is excluded: the wait for the fence runs with
// the timer paused. On lavapipe/llvmpipe the "GPU" is the CPU, so the figures are labelled
// software-rasterizer numbers; the ratio abstract/direct is what matters and is printed at the end.
#include <benchmark/benchmark.h>
#include <dlfcn.h>
#include <vulkan/vulkan.h>

#include <algorithm>
#include <ctime>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <memory>

#include "fe/gdi/Backend.h"
#include "gl/GlBackend.h"
#include "fe/gdi/ShaderRegistry.h"

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define FE_HAVE_CALLGRIND 1
#else
#define FE_HAVE_CALLGRIND 0
#endif

using namespace fe::gdi;

namespace {

constexpr uint32_t kDraws = 10000;
constexpr uint32_t kObjectStride = 256;  // >= every device's uniform offset alignment

struct Scene {
    std::unique_ptr<Device> device;
    TextureHandle target;
    BufferHandle vertices, objects;
    PipelineHandle pipeline;
    std::unique_ptr<CommandList> cmd;
};

// Off when measuring (the layers would dominate the cost); on for --check, which is a test.
bool validateScenes = false;

Scene makeScene(const std::string& backend) {
    Scene s;
    s.device = createDevice({.backend = backend, .validation = validateScenes, .verbose = false});
    Device& d = *s.device;
    // 100 x 100 pixels, one per draw: draw i covers exactly pixel (i % 100, i / 100) (legs of
    // 1.5 pixels from the pixel's corner reach its centre and no other), so --check sees every draw.
    s.target = d.createTexture({.format = Format::RGBA8,
                                .width = 100,
                                .height = 100,
                                .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc,
                                .debugName = "bench target"});
    const float tri[] = {0, 0, 1, 0, 0, 1};
    s.vertices = d.createBuffer({.size = sizeof(tri), .usage = BufferUsage::Vertex}, bytesOf(tri));
    std::vector<float> objects(kDraws * kObjectStride / 4, 0.0f);
    for (uint32_t i = 0; i < kDraws; ++i) {
        float* o = &objects[i * kObjectStride / 4];
        o[0] = -1.0f + 2.0f * float(i % 100) / 100.0f;  // offset
        o[1] = -1.0f + 2.0f * float(i / 100) / 100.0f;
        o[2] = o[3] = 0.03f;  // scale: 1.5 pixels
        o[4] = float(i % 7) / 7.0f, o[5] = 0.5f, o[6] = 1.0f, o[7] = 1.0f;
    }
    s.objects = d.createBuffer({.size = objects.size() * 4, .usage = BufferUsage::Uniform},
                               bytesOf(objects));
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("bench/draw.vert")});
    auto fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("bench/draw.frag")});
    s.pipeline = d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .vertexBuffers = {{.stride = 8,
                            .attributes = {{.location = 0, .format = VertexFormat::Float2}}}},
         .colorFormats = {Format::RGBA8},
         .debugName = "bench draw"});
    s.cmd = d.createCommandList();
    return s;
}

// One cached scene per backend: device creation is not what is measured. main() clears them
// before returning: at exit, the GL drivers' own teardown may already have run.
std::map<std::string, Scene>& scenes() {
    static std::map<std::string, Scene> all;
    return all;
}
Scene& scene(const std::string& backend) {
    auto it = scenes().find(backend);
    if (it == scenes().end()) it = scenes().emplace(backend, makeScene(backend)).first;
    return it->second;
}

// One frame of a path, split so that only recording and submission are measured.
struct FramePath {
    std::function<void()> record;  // every draw of the frame
    std::function<void()> submit;  // hand the frame to the queue
    std::function<void()> wait;    // GPU execution: never measured
};

FramePath abstractPath(Scene& s) {
    auto fence = std::make_shared<FenceValue>(0);
    return {.record =
                [&s] {
                    CommandList& c = *s.cmd;
                    c.beginRenderPass({.colors = {{.texture = s.target, .clear = {0, 0, 0, 1}}}});
                    c.setPipeline(s.pipeline);
                    c.setVertexBuffer(0, s.vertices);
                    for (uint32_t i = 0; i < kDraws; ++i) {
                        c.setUniformBuffer(0, s.objects, uint64_t(i) * kObjectStride, 64);
                        c.draw(3);
                    }
                    c.endRenderPass();
                },
            .submit =
                [&s, fence] {
                    *fence = s.device->submit(*s.cmd);
                    // GL replays the stream on its context thread after submit returns: the
                    // replay is part of the abstraction's cost, so submit counts until it ran
                    // (not the GPU's execution: that is the wait's).
                    if (s.device->info().backend != "vulkan")
                        fe::gl::runOnContextThread(*s.device, [] {});
                },
            .wait = [&s, fence] { s.device->wait(*fence); }};
}

void runFrames(benchmark::State& state, Scene& s, const FramePath& path) {
    for (auto _ : state) {
        path.record();
        path.submit();
        state.PauseTiming();
        path.wait();
        state.ResumeTiming();
    }
    state.counters["ns_per_draw"] =
        benchmark::Counter(double(kDraws), benchmark::Counter::kIsIterationInvariantRate |
                                               benchmark::Counter::kInvert);
    state.SetLabel(s.device->info().softwareRasterizer ? "software rasterizer"
                                                       : s.device->info().deviceName);
}

// ---- direct Vulkan -------------------------------------------------------------------------
// Like the GL path below: the frame around the draws (command buffer begin, render pass,
// pipeline, submit) goes through the backend on both sides, once per frame; the 10,000 draws
// are recorded with direct Vulkan calls into the same command buffer. Sharing the command
// buffer also shares lavapipe's command allocator: with a pool of its own, the direct path's
// driver work depended on the heap's state (up to 16 % more instructions in some runs).
FramePath vulkanDirectPath(Scene& s) {
    Device& d = *s.device;
    const auto device = reinterpret_cast<VkDevice>(d.nativeObject(NativeObject::Device));
    const auto push = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(device, "vkCmdPushDescriptorSetKHR"));
    const auto layout = reinterpret_cast<VkPipelineLayout>(
        d.nativeObject(NativeObject::PipelineLayout, s.pipeline.id));
    const auto ubo = reinterpret_cast<VkBuffer>(d.nativeObject(NativeObject::Buffer, s.objects.id));
    if (!push || !layout || !ubo) throw Error("Vulkan backend does not expose native objects");
    auto fence = std::make_shared<FenceValue>(0);
    return {.record =
                [&s, push, layout, ubo] {
                    CommandList& c = *s.cmd;
                    c.beginRenderPass({.colors = {{.texture = s.target, .clear = {0, 0, 0, 1}}}});
                    c.setPipeline(s.pipeline);
                    c.setVertexBuffer(0, s.vertices);
                    const auto cb = reinterpret_cast<VkCommandBuffer>(c.nativeCommandBuffer());
                    for (uint32_t i = 0; i < kDraws; ++i) {
                        VkDescriptorBufferInfo info{ubo, VkDeviceSize(i) * kObjectStride, 64};
                        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
                        w.dstBinding = 0;
                        w.descriptorCount = 1;
                        w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
                        w.pBufferInfo = &info;
                        push(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &w);
                        vkCmdDraw(cb, 3, 1, 0, 0);
                    }
                    c.endRenderPass();
                },
            .submit = [&s, fence] { *fence = s.device->submit(*s.cmd); },
            .wait = [&s, fence] { s.device->wait(*fence); }};
}

// ---- direct GL -----------------------------------------------------------------------------
// GL entry points fetched through the same platform library the backend uses.
struct GlDirect {
    using UseProgram = void (*)(unsigned);
    using BindVertexArray = void (*)(unsigned);
    using BindBufferRange = void (*)(unsigned, unsigned, unsigned, intptr_t, intptr_t);
    using DrawArrays = void (*)(unsigned, int, int);
    using VertexArrayVertexBuffer = void (*)(unsigned, unsigned, unsigned, intptr_t, int);
    using DrawArraysInstancedBaseInstance = void (*)(unsigned, int, int, int, unsigned);
    UseProgram useProgram = nullptr;
    BindVertexArray bindVertexArray = nullptr;
    BindBufferRange bindBufferRange = nullptr;
    DrawArrays drawArrays = nullptr;
    VertexArrayVertexBuffer vertexArrayVertexBuffer = nullptr;
    DrawArraysInstancedBaseInstance drawArraysInstancedBaseInstance = nullptr;

    explicit GlDirect(const std::string& backend) {
        using GetProc = void* (*)(const char*);
        GetProc get = nullptr;
        if (backend == "gl-egl") {
            void* lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_GLOBAL);
            if (lib) get = reinterpret_cast<GetProc>(dlsym(lib, "eglGetProcAddress"));
        } else {
            void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_GLOBAL);
            if (lib) get = reinterpret_cast<GetProc>(dlsym(lib, "OSMesaGetProcAddress"));
        }
        if (!get) throw Error("bench: cannot load GL entry points for " + backend);
        useProgram = reinterpret_cast<UseProgram>(get("glUseProgram"));
        bindVertexArray = reinterpret_cast<BindVertexArray>(get("glBindVertexArray"));
        bindBufferRange = reinterpret_cast<BindBufferRange>(get("glBindBufferRange"));
        drawArrays = reinterpret_cast<DrawArrays>(get("glDrawArrays"));
        vertexArrayVertexBuffer =
            reinterpret_cast<VertexArrayVertexBuffer>(get("glVertexArrayVertexBuffer"));
        drawArraysInstancedBaseInstance = reinterpret_cast<DrawArraysInstancedBaseInstance>(
            get("glDrawArraysInstancedBaseInstance"));
    }
};

// `instanced`: each draw through glDrawArraysInstancedBaseInstance(..., 1, 0) instead, the entry
// point the replay used for every draw until 2026-11-30 (--paired prints what it costs the driver).
FramePath glDirectPath(Scene& s, const std::string& backend, bool instanced = false) {
    Device& d = *s.device;
    auto gl = std::make_shared<GlDirect>(backend);
    const unsigned program = unsigned(d.nativeObject(NativeObject::Pipeline, s.pipeline.id));
    const unsigned vao = unsigned(d.nativeObject(NativeObject::VertexArray, s.pipeline.id));
    const unsigned vb = unsigned(d.nativeObject(NativeObject::Buffer, s.vertices.id));
    const unsigned ubo = unsigned(d.nativeObject(NativeObject::Buffer, s.objects.id));
    if (!program || !vao || !vb || !ubo) throw Error("GL backend does not expose native objects");
    auto fence = std::make_shared<FenceValue>(0);
    return {.record =
                [&s, gl, program, vao, vb, ubo, instanced] {
                    constexpr unsigned GL_UNIFORM_BUFFER = 0x8A11, GL_TRIANGLES = 0x0004;
                    // The render pass itself (FBO bind, clear, pipeline state) goes through the
                    // backend on both sides: an empty pass leaves the framebuffer and state bound
                    // on the context thread, where the direct calls then run.
                    CommandList& c = *s.cmd;
                    c.beginRenderPass({.colors = {{.texture = s.target, .clear = {0, 0, 0, 1}}}});
                    c.setPipeline(s.pipeline);
                    c.endRenderPass();
                    s.device->submit(c);
                    fe::gl::runOnContextThread(*s.device, [&] {
                        gl->useProgram(program);
                        gl->bindVertexArray(vao);
                        gl->vertexArrayVertexBuffer(vao, 0, vb, 0, 8);
                        for (uint32_t i = 0; i < kDraws; ++i) {
                            gl->bindBufferRange(GL_UNIFORM_BUFFER, 0, ubo,
                                                intptr_t(i) * kObjectStride, 64);
                            if (instanced)
                                gl->drawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 3, 1, 0);
                            else
                                gl->drawArrays(GL_TRIANGLES, 0, 3);
                        }
                    });
                },
            .submit = [&s, fence] { *fence = s.device->submit(*s.cmd); },
            .wait = [&s, fence] { s.device->wait(*fence); }};
}

FramePath directPath(Scene& s, const std::string& backend) {
    return backend == "vulkan" ? vulkanDirectPath(s) : glDirectPath(s, backend);
}

// Prints abstract/direct ratios after the normal console table.
class RatioReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& r : runs) {
            if (r.run_type != Run::RT_Aggregate || r.aggregate_name != "median") continue;
            std::string name = r.benchmark_name();
            times_[name] = r.GetAdjustedCPUTime();
        }
    }
    void Finalize() override {
        ConsoleReporter::Finalize();
        std::cout << "\nabstraction cost (median CPU time, abstract / direct):\n";
        for (const char* b : {"vulkan", "gl-egl", "gl-osmesa"}) {
            double a = find(std::string("Abstract/") + b), d = find(std::string("Direct/") + b);
            if (a > 0 && d > 0)
                std::cout << "  " << b << ": " << a / kDraws * 1e6 << " ns/draw vs "
                          << d / kDraws * 1e6 << " ns/draw -> ratio " << a / d << " ("
                          << (a / d - 1.0) * 100.0 << "% overhead)\n";
        }
    }

private:
    double find(const std::string& prefix) const {
        for (auto& [k, v] : times_)
            if (k.rfind(prefix, 0) == 0) return v;
        return 0;
    }
    std::map<std::string, double> times_;
};

}  // namespace

// --count-instructions: under `valgrind --tool=callgrind --collect-atstart=no`, counts the
// instructions the calling thread executes while recording, and while recording + submitting,
// each of a path's frames (after one warm-up frame), and dumps each frame's count as its own
// callgrind profile. Instruction counts are repeatable where time on a shared 2-core machine is not;
// tools/bench-abstraction-instructions.sh runs this and prints the ratios.
int countInstructions(uint32_t frames) {
#if FE_HAVE_CALLGRIND
    if (!RUNNING_ON_VALGRIND) {
        std::cerr
            << "--count-instructions must run under valgrind --tool=callgrind --collect-atstart=no "
               "(tools/bench-abstraction-instructions.sh does)\n";
        return 2;
    }
    for (const std::string& b : backendNames()) {
        if (!probeBackend(b, false).available) continue;
        Scene& s = scene(b);
        for (const char* kind : {"abstract", "direct"}) {
            FramePath path = std::string(kind) == "abstract" ? abstractPath(s) : directPath(s, b);
            path.record(), path.submit(), path.wait();  // warm-up: first-use allocations
            for (int withSubmit = 0; withSubmit < 2; ++withSubmit) {
                const std::string name =
                    b + " " + kind + (withSubmit ? " record+submit" : " record");
                for (uint32_t f = 0; f < frames; ++f) {
                    const std::string frame = name + " #" + std::to_string(f);
                    // Collection is a per-thread state in callgrind: on GL the context thread's is
                    // switched too, around the recording thread's window.
                    auto toggleContextThread = [&] {
                        if (b != "vulkan")
                            fe::gl::runOnContextThread(*s.device, [] { CALLGRIND_TOGGLE_COLLECT; });
                    };
                    toggleContextThread();
                    CALLGRIND_TOGGLE_COLLECT;
                    path.record();
                    if (withSubmit) path.submit();
                    CALLGRIND_TOGGLE_COLLECT;
                    toggleContextThread();
                    // One profile per frame and thread (a dump covers the calling thread only): the
                    // recording thread's, and on GL the context thread's, which replays the lists
                    // and makes the direct path's calls. The script sums a frame's profiles.
                    CALLGRIND_DUMP_STATS_AT(frame.c_str());
                    if (b != "vulkan")
                        fe::gl::runOnContextThread(*s.device,
                                                   [&] { CALLGRIND_DUMP_STATS_AT(frame.c_str()); });
                    if (!withSubmit) path.submit();
                    path.wait();
                }
            }
        }
    }
    std::cout << "frames " << frames << " draws " << kDraws << "\n";  // draws per frame
    return 0;
#else
    std::cerr
        << "--count-instructions needs valgrind/callgrind.h at build time (apt-get install valgrind)\n";
    return 2;
#endif
}

// --check: the two paths must do the same work. Renders one frame with each on every backend
// and compares the images byte for byte (run by ctest as bench_paths_draw_the_same).
int checkSameImage() {
    validateScenes = true;
    int failures = 0;
    for (const std::string& b : backendNames()) {
        if (!probeBackend(b, false).available) continue;
        Scene& s = scene(b);
        Image images[2];
        FramePath paths[2] = {abstractPath(s), directPath(s, b)};
        for (int k = 0; k < 2; ++k) {
            paths[k].record(), paths[k].submit(), paths[k].wait();
            images[k] = s.device->readTexture(s.target);
        }
        size_t lit = 0;
        for (size_t i = 0; i < images[0].data.size(); i += 4)
            lit += images[0].data[i + 2] != 0;  // blue = 1 where drawn
        const bool same = images[0].data == images[1].data;
        const uint32_t errors = s.device->validationErrorCount();
        if (errors) std::cout << b << ": " << errors << " validation error(s)\n";
        failures += errors != 0;
        std::cout << b << ": abstract and direct images " << (same ? "identical" : "DIFFER") << ", "
                  << lit << " pixels drawn\n";
        if (lit != kDraws)
            std::cout << b << ": expected one pixel per draw, " << kDraws << " pixels\n";
        failures += !same || lit != kDraws;
    }
    return failures ? 1 : 0;
}

// --paired N: N pairs of frames per backend, abstract and direct alternating (which goes first
// alternates too), each frame's record+submit timed with the CPU clocks of the recording thread
// and, on GL, of the device's context thread, where both paths' GL calls run (the abstract
// path's replay, the direct path's own calls). The recording thread's clock alone compared
// recording a stream against waiting for the context thread: 9.9 x on an H100 (2026-11-27).
// The ratio is taken per pair and the median reported: drift of the machine between separate
// benchmark runs (seen at 5-10 % here) cancels within a pair.
double threadSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

// Besides the ratio, where each path's time went: the recording thread and GL's context thread
// apart (the direct path's calls all run on the context thread), and on GL a third path, direct
// calls through glDrawArraysInstancedBaseInstance, timed in the same rotation: what the
// instanced entry point costs the driver over glDrawArrays.
int pairedRatios(uint32_t pairs) {
    std::cout
        << "abstraction cost, " << pairs << " pairs of frames of " << kDraws
        << " draws, CPU time of the recording thread (and GL's context thread), median (and quartiles) of per-pair "
           "abstract / direct:\n";
    auto quantile = [](std::vector<double> v, double q) {
        std::sort(v.begin(), v.end());
        return v[size_t(q * double(v.size() - 1) + 0.5)];
    };
    for (const std::string& b : backendNames()) {
        if (!probeBackend(b, false).available) continue;
        Scene& s = scene(b);
        const bool gl = b != "vulkan";
        std::vector<FramePath> paths = {abstractPath(s), directPath(s, b)};
        if (gl) paths.push_back(glDirectPath(s, b, true));
        const size_t n = paths.size();
        // Read on the context thread once the frame's calls ran there (it runs tasks in order).
        auto contextSeconds = [&] {
            double v = 0;
            if (gl) fe::gl::runOnContextThread(*s.device, [&] { v = threadSeconds(); });
            return v;
        };
        for (FramePath& p : paths) p.record(), p.submit(), p.wait();  // warm-up
        std::vector<double> ratios, instancedRatios;
        std::vector<std::vector<double>> recordingNs(n), contextNs(n), totalNs(n);
        for (uint32_t i = 0; i < pairs; ++i) {
            std::vector<double> t(n);
            for (size_t k = 0; k < n; ++k) {
                const size_t which = (k + i) % n;  // each path goes first as often
                const double c0 = contextSeconds(), t0 = threadSeconds();
                paths[which].record();
                paths[which].submit();
                const double recording = threadSeconds() - t0, context = contextSeconds() - c0;
                t[which] = recording + context;
                recordingNs[which].push_back(recording / kDraws * 1e9);
                contextNs[which].push_back(context / kDraws * 1e9);
                totalNs[which].push_back(t[which] / kDraws * 1e9);
                paths[which].wait();
            }
            ratios.push_back(t[0] / t[1]);
            if (gl) instancedRatios.push_back(t[2] / t[1]);
        }
        std::cout << "  " << b
                  << (s.device->info().softwareRasterizer ? " (software rasterizer)" : "") << ": "
                  << quantile(totalNs[0], 0.5) << " vs " << quantile(totalNs[1], 0.5)
                  << " ns/draw, ratio " << quantile(ratios, 0.5) << " (quartiles "
                  << quantile(ratios, 0.25) << " - " << quantile(ratios, 0.75) << ")\n";
        if (!gl) continue;
        std::cout << "    medians, ns/draw: abstract " << quantile(recordingNs[0], 0.5)
                  << " recording + " << quantile(contextNs[0], 0.5) << " context thread; direct "
                  << quantile(recordingNs[1], 0.5) << " + " << quantile(contextNs[1], 0.5)
                  << "; direct through glDrawArraysInstancedBaseInstance "
                  << quantile(totalNs[2], 0.5) << ", ratio to direct "
                  << quantile(instancedRatios, 0.5) << "\n";
    }
    return 0;
}

int main(int argc, char** argv) {
    // The two measuring modes besides Google Benchmark: MODE [N].
    const std::string mode = argc >= 2 ? argv[1] : "";
    if (mode == "--check" || mode == "--count-instructions" || mode == "--paired") {
        const int n = argc >= 3 ? std::atoi(argv[2]) : 0;
        try {
            const int rc = mode == "--check"    ? checkSameImage()
                           : mode == "--paired" ? pairedRatios(n >= 2 ? uint32_t(n) : 200)
                                                : countInstructions(n >= 1 ? uint32_t(n) : 3);
            scenes().clear();
            return rc;
        } catch (const std::exception& e) {
            std::cerr << "fe_bench_abstraction: " << e.what() << "\n";
            return 1;
        }
    }
    benchmark::Initialize(&argc, argv);
    for (const std::string& b : backendNames()) {
        BackendProbe p = probeBackend(b, false);
        if (!p.available) {
            std::cerr << "skipping " << b << ": " << p.reason << "\n";
            continue;
        }
        p.device.reset();
        // Interleaved registration (abstract, direct per backend) so both see the same machine state.
        auto reg = [](benchmark::internal::Benchmark* bm) {
            bm->Unit(benchmark::kMillisecond)
                ->Repetitions(5)
                ->ReportAggregatesOnly(true)
                ->MinTime(0.5);
        };
        reg(benchmark::RegisterBenchmark(("Abstract/" + b).c_str(), [b](benchmark::State& st) {
            Scene& s = scene(b);
            runFrames(st, s, abstractPath(s));
        }));
        reg(benchmark::RegisterBenchmark(("Direct/" + b).c_str(), [b](benchmark::State& st) {
            Scene& s = scene(b);
            runFrames(st, s, directPath(s, b));
        }));
    }
    RatioReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    scenes().clear();
}
