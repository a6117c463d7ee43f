#pragma once
// Runs `row(y)` for every y in [0, height) on every core, rows interleaved so that costly
// regions (a scene's busy middle) spread evenly. Each row must write only its own outputs; the
// result is the same as a serial loop. The first exception a worker throws is rethrown here.
#include <algorithm>
#include <cstdint>
#include <exception>
#include <thread>
#include <vector>

namespace fe::render {

template <class RowFn>
void forEachRowInParallel(uint32_t height, RowFn&& row) {
    const uint32_t threads =
        std::clamp(std::thread::hardware_concurrency(), 1u, std::max(height, 1u));
    std::vector<std::exception_ptr> failures(threads);
    auto rows = [&](uint32_t first) {
        try {
            for (uint32_t y = first; y < height; y += threads) row(y);
        } catch (...) {
            failures[first] = std::current_exception();
        }
    };
    std::vector<std::thread> workers;
    for (uint32_t t = 1; t < threads; ++t) workers.emplace_back(rows, t);
    rows(0);
    for (std::thread& w : workers) w.join();
    for (const std::exception_ptr& e : failures)
        if (e) std::rethrow_exception(e);
}

}  // namespace fe::render
