// The execution model's figures (issue 24), per backend, medians over repeated rounds:
//  1. Parallel recording: 20,000 draws (a uniform-buffer slice and a draw each) recorded as one
//     list on one thread, against four lists of 5,000 on two threads (the calling thread and a
//     job thread, two lists each), and against one pass whose draws are four secondary lists
//     recorded on two threads and executed by a primary list, and that pass again with the
//     lists as recorded (bundles: only the primary's recording). Only the recording is timed
//     (executeSecondary included); the ratios two-thread / one-thread are the figures, each the
//     median of the rounds' own ratios: a round records one way right after the other, so a slow
//     phase of the machine (here they last several rounds and change the one-thread time up to
//     2x) slows both sides of its ratio, where a ratio of two medians would mix phases. The job
//     thread is awake when the recording starts (as mid-frame); its wake-up from sleep is a
//     column of its own.
//  2. CPU/GPU overlap: frames of 5,000 draws, recorded and submitted with two frames in flight,
//     against the same frames each waited for before the next is recorded. Record, submit and
//     wait are timed apart; with overlap the pipelined frame costs less than record + execute.
//  3. Churn: the frame time of (2) with two frames in flight, plain and while 1,000 textures are
//     created and destroyed (50 per frame over 20 frames).
//  4. Async compute (issue 50): a frame of 5,000 draws on the graphics queue and a compute job
//     (bench/busy.comp, 65,536 invocations, its loop sized to take about the frame's time) on
//     the compute queue, submitted with no wait between
//     them, against the same two one after the other on the graphics queue; from the first
//     submit to both fences, lists recorded beforehand. Below 1 only where the compute queue is
//     a hardware queue of its own (DeviceFeatures::asyncCompute) and the GPU has room beside the
//     frame; lavapipe and GL share one queue, so about 1 there.
// Each frame starts with --cpu-ms of application work (a busy loop), which frames in flight
// overlap with the previous frame's execution.
// Prints a markdown table. On lavapipe/llvmpipe the "GPU" is the same two CPU cores, so these
// are software-rasterizer figures: ratios measured in one run, not absolute speeds.
//   fe_bench_execution [--backend NAME|all] [--rounds N] [--cpu-ms MS]
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <exception>
#include <atomic>
#include <functional>
#include <string>
#include <thread>
#include <utility>

#include <pthread.h>
#include <sched.h>
#include <vector>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe::gdi;

namespace {

constexpr uint32_t kDraws = 20000;
constexpr uint32_t kStride = 256;  // >= every device's uniform offset alignment
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}
double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

struct Scene {
    std::unique_ptr<Device> device;
    TextureHandle target;
    BufferHandle vertices, objects;
    PipelineHandle pipeline;
    ShaderHandle vs, fs;
    explicit Scene(const std::string& backend) {
        device = createDevice({.backend = backend, .validation = false, .verbose = false});
        Device& d = *device;
        target = d.createTexture({.width = 100,
                                  .height = 100,
                                  .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
        const float tri[] = {0, 0, 1, 0, 0, 1};
        vertices =
            d.createBuffer({.size = sizeof(tri), .usage = BufferUsage::Vertex}, bytesOf(tri));
        std::vector<float> o(size_t(kDraws) * kStride / 4, 0.0f);
        for (uint32_t i = 0; i < kDraws; ++i) {
            float* p = &o[size_t(i) * kStride / 4];
            p[0] = -1 + 2 * float(i % 100) / 100, p[1] = -1 + 2 * float(i / 100 % 100) / 100,
            p[2] = p[3] = 0.03f;
            p[4] = p[5] = p[6] = p[7] = 1;
        }
        objects = d.createBuffer({.size = o.size() * 4, .usage = BufferUsage::Uniform}, bytesOf(o));
        vs = d.createShader(
            {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("bench/draw.vert")});
        fs = d.createShader(
            {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("bench/draw.frag")});
        pipeline = d.createGraphicsPipeline(
            {.vertexShader = vs,
             .fragmentShader = fs,
             .vertexBuffers = {{.stride = 8,
                                .attributes = {{.location = 0, .format = VertexFormat::Float2}}}},
             .colorFormats = {Format::RGBA8}});
    }
    ~Scene() {
        device->waitIdle();
        for (BufferHandle b : {vertices, objects}) device->destroy(b);
        device->destroy(target);
        device->destroy(pipeline);
        device->destroy(vs);
        device->destroy(fs);
    }
    // Draws [first, first + count) into the target; `clear` on the first list of a frame.
    void record(CommandList& c, uint32_t first, uint32_t count, bool clear) const {
        c.beginRenderPass(
            {.colors = {{.texture = target, .load = clear ? LoadOp::Clear : LoadOp::Load}}});
        c.setPipeline(pipeline);
        c.setVertexBuffer(0, vertices);
        for (uint32_t i = first; i < first + count; ++i) {
            c.setUniformBuffer(0, objects, uint64_t(i) * kStride, 64);
            c.draw(3);
        }
        c.endRenderPass();
    }
    RenderPassDesc secondaryPass() const {
        return {.colors = {{.texture = target}}, .secondaryLists = true};
    }
    // The same draws as a secondary list of secondaryPass().
    void recordSecondary(CommandList& c, uint32_t first, uint32_t count) const {
        c.beginSecondary(secondaryPass());
        c.setPipeline(pipeline);
        c.setVertexBuffer(0, vertices);
        for (uint32_t i = first; i < first + count; ++i) {
            c.setUniformBuffer(0, objects, uint64_t(i) * kStride, 64);
            c.draw(3);
        }
        c.endSecondary();
    }
};

struct Row {
    std::string backend;
    double oneThread = 0, twoThreads = 0, secondaryTwoThreads = 0, fromSleep = 0;  // medians, ms
    double twoRatio = 0, secondaryRatio = 0,
           fromSleepRatio = 0;  // medians of each round's ratio to oneThread
    double seqFrame = 0, pipeFrame = 0, record = 0, submit = 0, wait = 0;
    double plainFrame = 0, churnFrame = 0;
    double callerHalf = 0, workerHalf = 0;  // each thread's own two lists, in the 4-list rounds
    double secondaryReplayed = 0;  // the pass of 4 secondary lists again, recorded once, ms
    bool pinned = false;
    double frameAlone = 0, jobAlone = 0, serialQueues = 0, overlappedQueues = 0, queueRatio = 0;
    bool asyncCompute = false;
};

// A job thread that lives across rounds, as an engine's job threads do (threads made per round
// would hand their malloc arenas over, which is not what recording costs). While the frame's
// recording runs its workers are awake, as a job system's are mid-frame: the worker spins on
// the job counter between jobs of a phase and sleeps (atomic wait) outside the phases, so it
// steals no core from the "GPU" (lavapipe's and llvmpipe's threads on this machine) while the
// work executes. The wake-up from sleep is measured on its own (`fromSleep`).
// Pins the calling thread to one CPU (cpu >= 0) or lets it run on all of them again (-1). Job
// systems pin their workers: a thread woken by the thread it works beside is placed on the
// waker's core, and the two then share it while the other core idles (seen here: the job ran
// only after the caller's half had finished).
// CPUs are named by their place among the ones this process may use (a container's cpuset need
// not start at 0): 0 is the first allowed CPU, -2 the last, -1 all of them again. Returns false
// where the pin did not take (the figures then include the sharing described above).
bool pinCallingThread(int place) {
    static const cpu_set_t allowed = [] {
        cpu_set_t set;
        CPU_ZERO(&set);
        sched_getaffinity(0, sizeof(set), &set);
        return set;
    }();
    std::vector<int> cpus;
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
    if (place == -1 || cpus.size() < 2)
        return pthread_setaffinity_np(pthread_self(), sizeof(allowed), &allowed) == 0;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(place == -2 ? cpus.back() : cpus[size_t(place) % cpus.size()], &one);
    return pthread_setaffinity_np(pthread_self(), sizeof(one), &one) == 0;
}

class JobThread {
public:
    // The worker keeps to the last CPU; a caller of pinned phases keeps to the first.
    JobThread()
        : thread_([this] {
              pinned_ = pinCallingThread(-2);
              run();
          }) {}
    ~JobThread() {
        stop_ = true;
        signal();
        thread_.join();
    }
    // Keeps the worker spinning until sleep(), and the caller on the first CPU; returns once the
    // worker spins.
    void wake() {
        callerPinned_ = pinCallingThread(0);
        awake_ = true;
        signal();
        while (!spinning_) std::this_thread::yield();
    }
    // Whether both threads kept to their own CPUs (the worker's pin is set as it starts).
    bool pinned() const { return pinned_ && callerPinned_; }
    void sleep() {
        awake_ = false;
        pinCallingThread(-1);
    }
    // Runs `job` on the worker; join() waits for it (spinning: the caller is mid-frame too).
    void start(std::function<void()> job) {
        job_ = std::move(job);
        pending_.store(true, std::memory_order_release);
        signal();
    }
    void join() {
        while (pending_.load(std::memory_order_acquire)) std::this_thread::yield();
        if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    }

private:
    void signal() {
        signals_.fetch_add(1);
        signals_.notify_one();
    }
    void run() {
        for (;;) {
            const uint32_t seen =
                signals_.load();  // before the checks: a signal after them ends the wait
            if (stop_) return;
            if (pending_.load(std::memory_order_acquire)) {
                try {
                    job_();
                } catch (...) {
                    error_ = std::current_exception();
                }
                pending_.store(false, std::memory_order_release);
            } else if (awake_) {
                // Yielding, not pausing: a spinning thread that never yields is the first the
                // scheduler preempts when the driver's threads wake, for a whole time slice.
                spinning_ = true;
                std::this_thread::yield();
            } else {
                spinning_ = false;
                signals_.wait(seen);
            }
        }
    }
    std::atomic<uint32_t> signals_{0};
    std::atomic<bool> awake_{false}, spinning_{false}, pending_{false}, stop_{false};
    std::atomic<bool> pinned_{false};
    bool callerPinned_ = false;
    std::function<void()> job_;
    std::exception_ptr error_;
    std::thread thread_;
};

// 20,000 draws: one list on one thread, then four lists on two threads (this thread records two,
// the job thread the other two), then one pass of four secondary lists likewise. `fromSleep`
// repeats the four lists with the job thread asleep when the recording starts.
void parallelRecording(Scene& s, uint32_t rounds, Row& row) {
    Device& d = *s.device;
    std::vector<double> one, two, parts, cold, callerHalves, workerHalves, replayed;
    auto single = d.createCommandList();
    std::array<std::unique_ptr<CommandList>, 4> quarter = {
        d.createCommandList(), d.createCommandList(), d.createCommandList(), d.createCommandList()};
    std::array<CommandList*, 4> all = {quarter[0].get(), quarter[1].get(), quarter[2].get(),
                                       quarter[3].get()};
    auto primary = d.createCommandList();
    JobThread worker;
    auto halves = [&](bool secondary, bool keepHalves = false) {
        auto recordPair = [&](uint32_t first) {
            for (uint32_t l = first; l < first + 2; ++l)
                if (secondary)
                    s.recordSecondary(*quarter[l], l * kDraws / 4, kDraws / 4);
                else
                    s.record(*quarter[l], l * kDraws / 4, kDraws / 4, l == 0);
        };
        double workerMs = 0;
        Clock::time_point t0 = Clock::now();
        worker.start([&] {
            const Clock::time_point tw = Clock::now();
            recordPair(2);
            workerMs = msSince(tw);
        });
        recordPair(0);
        const double callerMs = msSince(t0);
        worker.join();
        if (keepHalves) callerHalves.push_back(callerMs), workerHalves.push_back(workerMs);
    };
    for (uint32_t r = 0; r < rounds + 1; ++r) {  // round 0 warms every path up
        Clock::time_point t = Clock::now();
        s.record(*single, 0, kDraws, true);
        if (r) one.push_back(msSince(t));
        d.wait(d.submit(*single));

        worker.wake();
        t = Clock::now();
        halves(false, r > 0);
        if (r) two.push_back(msSince(t));
        worker.sleep();
        d.wait(d.submit(all));

        worker.wake();
        t = Clock::now();
        primary->beginRenderPass(s.secondaryPass());
        halves(true);
        primary->executeSecondary(all);
        primary->endRenderPass();
        if (r) parts.push_back(msSince(t));
        worker.sleep();
        d.wait(d.submit(*primary));

        t = Clock::now();  // the same four lists run again, recorded once (bundles)
        primary->beginRenderPass(s.secondaryPass());
        primary->executeSecondary(all);
        primary->endRenderPass();
        if (r) replayed.push_back(msSince(t));
        d.wait(d.submit(*primary));
        for (auto& l : quarter) l->reset();  // primary lists again

        std::this_thread::sleep_for(
            std::chrono::milliseconds(1));  // the job thread is asleep by now
        t = Clock::now();
        halves(false);
        if (r) cold.push_back(msSince(t));
        d.wait(d.submit(all));
    }
    // Both ways drew every draw: each of the 10,000 pixels is covered (the last round's image).
    const Image image = d.readTexture(s.target);
    uint32_t lit = 0;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) lit += image.texel(x, y)[0] > 0.5f;
    if (lit != 10000)
        throw Error("parallel recording drew " + std::to_string(lit) + " of 10000 pixels");
    auto ratios = [&](const std::vector<double>& two) {
        std::vector<double> r;
        for (size_t i = 0; i < two.size(); ++i) r.push_back(two[i] / one[i]);
        return median(r);
    };
    row.twoRatio = ratios(two), row.secondaryRatio = ratios(parts),
    row.fromSleepRatio = ratios(cold);
    row.oneThread = median(one);
    row.twoThreads = median(two);
    row.secondaryTwoThreads = median(parts);
    row.secondaryReplayed = median(replayed);
    row.fromSleep = median(cold);
    row.callerHalf = median(callerHalves);
    row.workerHalf = median(workerHalves);
    row.pinned = worker.pinned();
}

// The application's own CPU work per frame (simulation, culling), a busy loop of `ms`.
void applicationWork(double ms) {
    const Clock::time_point t = Clock::now();
    while (msSince(t) < ms) {}
}

// Frames of kDraws / 4 draws after `cpuMs` of application work: `inFlight` 1 waits for each
// frame before the next begins; with 2 the next frame's work and recording overlap this one's
// execution (GL: its replay on the context thread and the rasterizer).
double frames(Scene& s, uint32_t count, uint32_t inFlight, Row* split, uint32_t churnPerFrame,
              double cpuMs) {
    Device& d = *s.device;
    std::vector<std::unique_ptr<CommandList>> lists;
    for (uint32_t i = 0; i < inFlight; ++i) lists.push_back(d.createCommandList());
    std::vector<FenceValue> fences(inFlight, 0);
    std::vector<double> frameMs, recordMs, submitMs, waitMs;
    for (uint32_t f = 0; f < count + 2; ++f) {  // two warm-up frames
        const Clock::time_point start = Clock::now();
        Clock::time_point t = start;
        d.wait(fences[f % inFlight]);
        const double w = msSince(t);
        for (uint32_t c = 0; c < churnPerFrame; ++c)
            d.destroy(d.createTexture({.width = 64,
                                       .height = 64,
                                       .usage = TextureUsage::Sampled | TextureUsage::CopyDst}));
        applicationWork(cpuMs);
        t = Clock::now();
        s.record(*lists[f % inFlight], 0, kDraws / 4, true);
        const double r = msSince(t);
        t = Clock::now();
        fences[f % inFlight] = d.submit(*lists[f % inFlight]);
        const double sub = msSince(t);
        if (f < 2) continue;
        frameMs.push_back(msSince(start)), recordMs.push_back(r), submitMs.push_back(sub),
            waitMs.push_back(w);
    }
    d.waitIdle();
    if (split)
        split->record = median(recordMs), split->submit = median(submitMs),
        split->wait = median(waitMs);
    return median(frameMs);
}

// Section 4: see the top. Each round times the serial and the overlapped form back to back and
// takes their ratio (the figure is the median of those ratios, as in section 1).
void asyncComputeOverlap(Scene& s, uint32_t rounds, Row& row) {
    Device& d = *s.device;
    row.asyncCompute = d.info().features.asyncCompute;
    const ShaderHandle cs = d.createShader(
        {.stage = ShaderStage::Compute, .binary = fe::shaders::find("bench/busy.comp")});
    const PipelineHandle busy = d.createComputePipeline({.computeShader = cs});
    constexpr uint32_t kInvocations = 65536;
    uint32_t iterations = 100;  // then scaled so that the job alone takes about the frame's time
    const BufferHandle results =
        d.createBuffer({.size = kInvocations * 4, .usage = BufferUsage::Storage});
    auto graphics = d.createCommandList();
    auto onGraphics = d.createCommandList();
    auto onCompute = d.createCommandList({.queue = QueueKind::Compute});
    auto job = [&](CommandList& c) {
        c.setPipeline(busy);
        c.setStorageBuffer(0, results);
        c.setConstants(iterations);
        c.dispatch(kInvocations / 64);
    };
    auto timed = [&](CommandList* jobList) {
        s.record(*graphics, 0, kDraws / 4, true);
        if (jobList) job(*jobList);
        const Clock::time_point t = Clock::now();
        FenceValue last = d.submit(*graphics);
        if (jobList) last = d.submit(*jobList);
        d.wait(last);
        return msSince(t);
    };
    auto jobOnly = [&] {
        job(*onCompute);
        const Clock::time_point t = Clock::now();
        d.wait(d.submit(*onCompute));
        return msSince(t);
    };
    (void)timed(nullptr), (void)jobOnly();  // warm-up
    const double frame = timed(nullptr), job100 = jobOnly();
    iterations = uint32_t(std::clamp(100.0 * frame / std::max(job100, 1e-3), 10.0, 1e6));
    std::vector<double> alone, jobs, serial, overlapped, ratios;
    for (uint32_t r = 0; r < rounds + 1; ++r) {  // one warm-up round
        const double a = timed(nullptr), j = jobOnly(), se = timed(onGraphics.get()),
                     ov = timed(onCompute.get());
        if (r == 0) continue;
        alone.push_back(a), jobs.push_back(j), serial.push_back(se), overlapped.push_back(ov);
        ratios.push_back(ov / se);
    }
    d.waitIdle();
    d.destroy(results);
    d.destroy(busy);
    d.destroy(cs);
    row.frameAlone = median(alone), row.jobAlone = median(jobs);
    row.serialQueues = median(serial), row.overlappedQueues = median(overlapped);
    row.queueRatio = median(ratios);
}

}  // namespace

int main(int argc, char** argv) {
    std::string which = "all";
    uint32_t rounds = 9;
    double cpuMs = 1.0;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc)
            which = argv[++i];
        else if (a == "--rounds" && i + 1 < argc)
            rounds = uint32_t(std::max(1, std::atoi(argv[++i])));
        else if (a == "--cpu-ms" && i + 1 < argc)
            cpuMs = std::max(0.0, std::atof(argv[++i]));
        else {
            std::fprintf(stderr, "usage: %s [--backend NAME|all] [--rounds N] [--cpu-ms MS]\n",
                         argv[0]);
            return 2;
        }
    }
    try {
        std::vector<Row> rows;
        for (const std::string& b : expandBackendList(which)) {
            if (!probeBackend(b, false).available) continue;
            Scene s(b);
            Row row{.backend = b};
            parallelRecording(s, rounds, row);
            row.seqFrame = frames(s, 2 * rounds, 1, nullptr, 0, cpuMs);
            row.pipeFrame = frames(s, 2 * rounds, 2, &row, 0, cpuMs);
            row.plainFrame = frames(s, 20, 2, nullptr, 0, cpuMs);
            row.churnFrame = frames(s, 20, 2, nullptr, 50, cpuMs);
            asyncComputeOverlap(s, rounds, row);
            rows.push_back(row);
        }
        std::printf(
            "Parallel recording (%u rounds; times are medians, a ratio is the median of the rounds' own ratios)\n\n"
            "| backend | 20,000 draws, 1 list on 1 thread, ms | 4 lists on 2 threads, ms | ratio | 1 pass of 4 "
            "secondary lists on 2 threads, ms | ratio | 4 lists, job thread woken from sleep, ms | ratio |\n"
            "|---|---|---|---|---|---|---|---|\n",
            rounds);
        for (const Row& r : rows)
            std::printf("| %s | %.3f | %.3f | **%.2f** | %.3f | **%.2f** | %.3f | %.2f |\n",
                        r.backend.c_str(), r.oneThread, r.twoThreads, r.twoRatio,
                        r.secondaryTwoThreads, r.secondaryRatio, r.fromSleep, r.fromSleepRatio);
        std::printf(
            "\nThe pass of 4 secondary lists executed again without recording them "
            "(bundles; the primary's recording only), medians, ms:\n");
        for (const Row& r : rows)
            std::printf("- %s: %.3f (recording them took %.3f)\n", r.backend.c_str(),
                        r.secondaryReplayed, r.secondaryTwoThreads);
        std::printf(
            "\nEach thread's own half of the 4 lists (medians, ms; a half alone would take half the first column):\n");
        for (const Row& r : rows)
            std::printf(
                "- %s: calling thread %.3f, job thread %.3f (start to end of its job); threads %s\n",
                r.backend.c_str(), r.callerHalf, r.workerHalf,
                r.pinned ? "pinned to the first and last allowed CPUs"
                         : "NOT pinned (the pin failed)");
        std::printf(
            "\nFrames of 5,000 draws after %.1f ms of application work (medians)\n\n| backend | 1 frame in flight, ms | "
            "2 in flight, ms | 2 in flight: record / submit / wait, ms | 2 in flight, again, ms | same, creating and "
            "destroying 50 textures per frame, ms |\n|---|---|---|---|---|---|\n",
            cpuMs);
        for (const Row& r : rows)
            std::printf("| %s | %.2f | %.2f | %.2f / %.2f / %.2f | %.2f | %.2f |\n",
                        r.backend.c_str(), r.seqFrame, r.pipeFrame, r.record, r.submit, r.wait,
                        r.plainFrame, r.churnFrame);
        std::printf(
            "\nAsync compute: a frame of 5,000 draws and a compute job, serial on the graphics queue "
            "against the job on the compute queue (medians of %u rounds; the ratio is the median of "
            "the rounds' own ratios)\n\n| backend | compute queue of its own | frame alone, ms | job "
            "alone, ms | both on the graphics queue, ms | job on the compute queue, ms | ratio |\n"
            "|---|---|---|---|---|---|---|\n",
            rounds);
        for (const Row& r : rows)
            std::printf("| %s | %s | %.2f | %.2f | %.2f | %.2f | **%.2f** |\n", r.backend.c_str(),
                        r.asyncCompute ? "yes" : "no (shares the graphics queue)", r.frameAlone,
                        r.jobAlone, r.serialQueues, r.overlappedQueues, r.queueRatio);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_bench_execution: %s\n", e.what());
        return 1;
    }
}
