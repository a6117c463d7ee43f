// The thread that owns a GL context (Filament's driver thread, bgfx's render thread): a GL
// context is current on one thread at a time, and gdi lets every device call come from any
// thread, so every GL call runs here. Synchronous calls (create, read) wait for their result;
// submitted command streams and destroys are queued and run in order while the caller goes on,
// which is also what gives GL the CPU/GPU overlap of frames in flight. Calls that do not depend
// on queued work (creation, waiting on a replayed fence) go ahead of it: runUrgent.
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <type_traits>
#include <utility>

namespace fe::gl {

class GlContextThread {
    struct Task {
        std::function<void()> run;
        bool oneOfARun = false;  // poll briefly for the next call afterwards
    };

public:
    GlContextThread() : thread_([this] { loop(); }) {}
    ~GlContextThread() { stop(); }

    bool onThisThread() const { return std::this_thread::get_id() == thread_.get_id(); }

    // Runs `task` after everything queued before it and returns its result (or rethrows).
    template <class F>
    auto run(F&& task) -> std::invoke_result_t<F&> {
        return runIn(tasks_, std::forward<F>(task), false);
    }
    // For calls whose result does not depend on queued work (creating an object, waiting on a
    // fence whose submission has been replayed): runs `task` before the queued tasks, and even
    // inside a long one (a replay services these between commands: serviceUrgent()).
    template <class F>
    auto runUrgent(F&& task) -> std::invoke_result_t<F&> {
        return runIn(urgent_, std::forward<F>(task), false);
    }
    // runUrgent for creating an object: a short call, which the caller polls for, and one of a
    // run (loading, per-frame churn), so afterwards this thread polls briefly for the next call
    // before it sleeps (see spinBriefly). Other calls sleep at once on both sides: a fence wait
    // or a read waits for the GPU, and after it the core is the caller's.
    template <class F>
    auto runCreation(F&& task) -> std::invoke_result_t<F&> {
        return runIn(urgent_, std::forward<F>(task), true);
    }
    // Set while urgent tasks wait: a long task on this thread polls it (one load) and calls
    // serviceUrgent() when it is set, so an urgent call waits one command, not a whole replay.
    const std::atomic<bool>& urgentWaiting() const { return urgentWaiting_; }
    // Called by long tasks on this thread: runs the urgent tasks waiting now.
    void serviceUrgent() {
        for (;;) {
            Task task;
            {
                std::lock_guard lock(mutex_);
                if (urgent_.empty()) return;
                task = std::move(urgent_.front());
                urgent_.pop_front();
                queued_.fetch_sub(1, std::memory_order_relaxed);
                urgentWaiting_.store(!urgent_.empty(), std::memory_order_relaxed);
            }
            task.run();  // runIn's wrapper catches and hands exceptions to the waiting caller
        }
    }
    // Whether this thread's tasks hold a lock every GL context thread of the process shares
    // (default: yes, until the device knows its driver). Mesa 22.3's llvmpipe is not safe with two
    // contexts making their first calls at once: two GL devices made and rendering on two threads
    // crashed a process in 1-3 of 12 runs on gl-egl and on gl-osmesa (a null function called inside
    // glClearTexImage while the other context compiled), 0 of 88 serialized (the tests
    // example_materials_*, eight processes each). A driver that is not a software rasterizer turns
    // it off (GlDevice), keeping its contexts in parallel.
    void serializeAcrossDevices(bool on) {
        serializeAcrossDevices_.store(on, std::memory_order_relaxed);
    }
    // Queues `task`; exceptions it throws are kept and rethrown by takeError().
    // `oneOfARun`: a call that others usually follow at once (destroying objects), after which
    // this thread polls briefly for the next before it sleeps, as after runCreation.
    void post(std::function<void()> task, bool oneOfARun = false) {
        push(tasks_, {std::move(task), oneOfARun});
    }
    // The first exception an asynchronous task threw since the last call, if any.
    std::exception_ptr takeError() {
        std::lock_guard lock(mutex_);
        return std::exchange(error_, nullptr);
    }
    void stop() {
        if (!thread_.joinable()) return;
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
            stopRequested_.store(true, std::memory_order_relaxed);
            cv_.notify_one();
        }
        thread_.join();
    }

private:
    template <class F>
    auto runIn(std::deque<Task>& queue, F&& task, bool oneOfARun) -> std::invoke_result_t<F&> {
        if (onThisThread()) return task();
        using R = std::invoke_result_t<F&>;
        std::mutex doneMutex;
        std::condition_variable doneCv;
        std::atomic<bool> done{false};
        std::exception_ptr error;
        std::conditional_t<std::is_void_v<R>, bool, std::optional<R>> result{};
        push(queue, {[&] {
                         try {
                             if constexpr (std::is_void_v<R>)
                                 task();
                             else
                                 result.emplace(task());
                         } catch (...) {
                             error = std::current_exception();
                         }
                         std::lock_guard lock(
                             doneMutex);  // notified under the lock: the caller's frame outlives it
                         done.store(true, std::memory_order_release);
                         doneCv.notify_one();
                     },
                     oneOfARun});
        if (oneOfARun)
            spinBriefly([&] { return done.load(std::memory_order_acquire); },
                        std::chrono::microseconds(50));
        std::unique_lock lock(doneMutex);  // also waits for the task's notify to finish
        doneCv.wait(lock, [&] { return done.load(std::memory_order_relaxed); });
        if (error) std::rethrow_exception(error);
        if constexpr (!std::is_void_v<R>) return std::move(*result);
    }
    // A synchronous call is a hand-over each way. Sleeping at once on both sides made each one
    // two futex sleeps and wake-ups (a texture create and destroy took 40 us on this VM, most of
    // it in the kernel's wake-up path, and frames that create objects paid it on the app
    // thread). So for a creation the caller polls for its result and this thread then for the
    // next call, each for about as long as a wake-up costs and yielding so the driver's own
    // threads keep the core, before sleeping.
    template <class Ready>
    static void spinBriefly(Ready&& ready, std::chrono::microseconds spin) {
        const auto until = std::chrono::steady_clock::now() + spin;
        for (uint32_t i = 0; !ready(); ++i) {
            if ((i & 15) == 15 && std::chrono::steady_clock::now() > until) return;
            std::this_thread::yield();
        }
    }
    void push(std::deque<Task>& queue, Task task) {
        std::lock_guard lock(mutex_);
        queued_.fetch_add(1, std::memory_order_release);
        queue.push_back(std::move(task));
        if (&queue == &urgent_) urgentWaiting_.store(true, std::memory_order_relaxed);
        cv_.notify_one();
    }
    void loop() {
        for (;;) {
            Task task;
            {
                std::unique_lock lock(mutex_);
                cv_.wait(lock, [&] { return stopping_ || !tasks_.empty() || !urgent_.empty(); });
                auto& queue = urgent_.empty() ? tasks_ : urgent_;
                if (queue.empty()) return;  // stopping, with everything run
                task = std::move(queue.front());
                queue.pop_front();
                queued_.fetch_sub(1, std::memory_order_relaxed);
                urgentWaiting_.store(!urgent_.empty(), std::memory_order_relaxed);
            }
            try {
                std::unique_lock processWide(processWideMutex(), std::defer_lock);
                if (serializeAcrossDevices_.load(std::memory_order_relaxed)) processWide.lock();
                task.run();
            } catch (...) {
                std::lock_guard lock(mutex_);
                if (!error_) error_ = std::current_exception();
            }
            if (task.oneOfARun)
                spinBriefly(
                    [&] {
                        return queued_.load(std::memory_order_acquire) != 0 ||
                               stopRequested_.load(std::memory_order_relaxed);
                    },
                    std::chrono::microseconds(20));
        }
    }
    static std::mutex& processWideMutex() {
        static std::mutex m;
        return m;
    }
    std::atomic<bool> serializeAcrossDevices_{true};
    std::mutex mutex_;
    std::condition_variable cv_;
    std::deque<Task> tasks_, urgent_;
    std::exception_ptr error_;
    std::atomic<bool> urgentWaiting_{false};  // !urgent_.empty(), written under mutex_
    std::atomic<uint32_t> queued_{0};         // tasks in both queues, written under mutex_
    std::atomic<bool> stopRequested_{false};  // stopping_, for the idle poll
    bool stopping_ = false;
    std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace fe::gl
