// parallel_rows.h — splits a row range over the host's cores for the per-body host work of a
// step (checks, row comparison, write-back, motion states). Each chunk gets its own index so
// callers collect results per chunk and merge them in order: the outcome does not depend on
// thread timing. The workers are started once and kept (a step runs several such passes, and
// starting a thread costs tens of microseconds).
#pragma once
#include <algorithm>
#include <cstddef>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace btgpu {

// Runs job(k) for k in [0, count): 0 on the calling thread, the rest on the pool's workers;
// returns when all are done. Calls from a worker, or while another thread's run is under way,
// run serially on the caller.
void runOnPool(size_t count, const std::function<void(size_t)>& job);

// Every cache line of the `bytes` at p fetched ahead of its use (write: for writing): the
// per-body passes over the app's objects, which lie scattered over the heap, wait for memory at
// every body without it. A hint only: it never faults, even on a pointer no longer valid.
inline void prefetchObject(const void* p, size_t bytes, bool write)
{
    const char* c = static_cast<const char*>(p);
    for (size_t off = 0; off < bytes; off += 64) {
        if (write) __builtin_prefetch(c + off, 1);
        else __builtin_prefetch(c + off, 0);
    }
}

// The per-body passes over the app's objects (the checks, the row comparison, the write-back,
// motion states) cost about 100-300 ns a body, mostly waiting for scattered objects: a chunk of
// this many is worth a pool thread's wake-up (tens of microseconds). At 4,096 a world of 8,000
// bodies ran them on one thread of a 16-core host (H100 run, cubes 8,000: write-back of the
// bodies 1.2 ms, sync-in 0.74).
constexpr size_t kBodyRowsPerThread = 1024;

// How many chunks forEachChunk will use for n rows (to size per-chunk result lists first).
inline int chunkCount(size_t n, size_t minPerThread)
{
    size_t hw = std::max<size_t>(1, std::thread::hardware_concurrency());
    return int(std::max<size_t>(1, std::min(hw, n / std::max<size_t>(minPerThread, 1))));
}

// Calls f(begin, end, chunk) on contiguous chunks covering [0, n); chunk 0 runs on the calling
// thread. Returns the number of chunks. Below minPerThread rows per thread it stays serial.
// An exception in any chunk is rethrown here after every chunk has finished (one escaping a
// worker thread would terminate the app).
template <typename F>
int forEachChunk(size_t n, size_t minPerThread, F f)
{
    const size_t chunks = size_t(chunkCount(n, minPerThread));
    const size_t per = (n + chunks - 1) / chunks;
    std::vector<std::exception_ptr> failed(chunks);
    auto run = [&](size_t k) {
        try {
            f(std::min(n, k * per), std::min(n, (k + 1) * per), int(k));
        } catch (...) {
            failed[k] = std::current_exception();
        }
    };
    if (chunks == 1) run(0);
    else runOnPool(chunks, run);
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
    return int(chunks);
}

}  // namespace btgpu
