// parallel_rows.h — splits a row range over the host's cores for the per-body host work of a
// step (write-back, motion states). Each chunk gets its own index so callers collect results
// per chunk and merge them in order: the outcome does not depend on thread timing.
#pragma once
#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace btgpu {

// Calls f(begin, end, chunk) on contiguous chunks covering [0, n); chunk 0 runs on the calling
// thread. Returns the number of chunks. Below minPerThread rows per thread it stays serial.
// An exception in any chunk is rethrown here after every thread has joined (one escaping a
// worker thread would terminate the app).
template <typename F>
int forEachChunk(size_t n, size_t minPerThread, F f)
{
    size_t hw = std::max<size_t>(1, std::thread::hardware_concurrency());
    size_t chunks = std::max<size_t>(1, std::min(hw, n / std::max<size_t>(minPerThread, 1)));
    size_t per = (n + chunks - 1) / chunks;
    std::vector<std::exception_ptr> failed(chunks);
    auto run = [&](size_t k) {
        try {
            f(std::min(n, k * per), std::min(n, (k + 1) * per), int(k));
        } catch (...) {
            failed[k] = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    for (size_t k = 1; k < chunks; ++k) threads.emplace_back(run, k);
    run(0);
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
    return int(chunks);
}

// How many chunks forEachChunk will use for n rows (to size per-chunk result lists first).
inline int chunkCount(size_t n, size_t minPerThread)
{
    size_t hw = std::max<size_t>(1, std::thread::hardware_concurrency());
    return int(std::max<size_t>(1, std::min(hw, n / std::max<size_t>(minPerThread, 1))));
}

}  // namespace btgpu
