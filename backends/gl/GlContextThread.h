// The thread that owns a GL context (Filament's driver thread, bgfx's render thread): a GL
// context is current on one thread at a time, and gdi lets every device call come from any
// thread, so every GL call runs here. Synchronous calls (create, read) wait for their result;
// submitted command streams and destroys are queued and run in order while the caller goes on,
// which is also what gives GL the CPU/GPU overlap of frames in flight. Calls that do not depend
// on queued work (creation, waiting on a replayed fence) go ahead of it: runUrgent.
#pragma once
#include <atomic>
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
public:
    GlContextThread() : thread_([this] { loop(); }) {}
    ~GlContextThread() { stop(); }

    bool onThisThread() const { return std::this_thread::get_id() == thread_.get_id(); }

    // Runs `task` after everything queued before it and returns its result (or rethrows).
    template <class F>
    auto run(F&& task) -> std::invoke_result_t<F&> {
        return runIn(tasks_, std::forward<F>(task));
    }
    // For calls whose result does not depend on queued work (creating an object, waiting on a
    // fence whose submission has been replayed): runs `task` before the queued tasks, and even
    // inside a long one (a replay services these between commands: serviceUrgent()).
    template <class F>
    auto runUrgent(F&& task) -> std::invoke_result_t<F&> {
        return runIn(urgent_, std::forward<F>(task));
    }
    // Set while urgent tasks wait: a long task on this thread polls it (one load) and calls
    // serviceUrgent() when it is set, so an urgent call waits one command, not a whole replay.
    const std::atomic<bool>& urgentWaiting() const { return urgentWaiting_; }
    // Called by long tasks on this thread: runs the urgent tasks waiting now.
    void serviceUrgent() {
        for (;;) {
            std::function<void()> task;
            {
                std::lock_guard lock(mutex_);
                if (urgent_.empty()) return;
                task = std::move(urgent_.front());
                urgent_.pop_front();
                urgentWaiting_.store(!urgent_.empty(), std::memory_order_relaxed);
            }
            task();  // runIn's wrapper catches and hands exceptions to the waiting caller
        }
    }
    // Queues `task`; exceptions it throws are kept and rethrown by takeError().
    void post(std::function<void()> task) { push(tasks_, std::move(task)); }
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
            cv_.notify_one();
        }
        thread_.join();
    }

private:
    template <class F>
    auto runIn(std::deque<std::function<void()>>& queue, F&& task) -> std::invoke_result_t<F&> {
        if (onThisThread()) return task();
        using R = std::invoke_result_t<F&>;
        std::mutex doneMutex;
        std::condition_variable doneCv;
        bool done = false;
        std::exception_ptr error;
        std::conditional_t<std::is_void_v<R>, bool, std::optional<R>> result{};
        push(queue, [&] {
            try {
                if constexpr (std::is_void_v<R>) task();
                else result.emplace(task());
            } catch (...) {
                error = std::current_exception();
            }
            std::lock_guard lock(doneMutex);
            done = true;
            doneCv.notify_one();
        });
        std::unique_lock lock(doneMutex);
        doneCv.wait(lock, [&] { return done; });
        if (error) std::rethrow_exception(error);
        if constexpr (!std::is_void_v<R>) return std::move(*result);
    }
    void push(std::deque<std::function<void()>>& queue, std::function<void()> task) {
        std::lock_guard lock(mutex_);
        queue.push_back(std::move(task));
        if (&queue == &urgent_) urgentWaiting_.store(true, std::memory_order_relaxed);
        cv_.notify_one();
    }
    void loop() {
        for (;;) {
            std::function<void()> task;
            {
                std::unique_lock lock(mutex_);
                cv_.wait(lock, [&] { return stopping_ || !tasks_.empty() || !urgent_.empty(); });
                auto& queue = urgent_.empty() ? tasks_ : urgent_;
                if (queue.empty()) return;  // stopping, with everything run
                task = std::move(queue.front());
                queue.pop_front();
                urgentWaiting_.store(!urgent_.empty(), std::memory_order_relaxed);
            }
            try {
                task();
            } catch (...) {
                std::lock_guard lock(mutex_);
                if (!error_) error_ = std::current_exception();
            }
        }
    }
    std::mutex mutex_;
    std::condition_variable cv_;
    std::deque<std::function<void()>> tasks_, urgent_;
    std::exception_ptr error_;
    std::atomic<bool> urgentWaiting_{false};  // !urgent_.empty(), written under mutex_
    bool stopping_ = false;
    std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace fe::gl
