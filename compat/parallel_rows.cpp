// parallel_rows.cpp — the host worker pool behind forEachChunk: hardware_concurrency - 1 threads
// started on first use, woken per run by a generation counter, each taking job indices from a
// shared counter until none are left.
#include "parallel_rows.h"

#include <atomic>
#include <condition_variable>
#include <mutex>

namespace btgpu {

namespace {

thread_local bool t_isWorker = false;

class Pool {
public:
    Pool()
    {
        const size_t hw = std::max<size_t>(1, std::thread::hardware_concurrency());
        for (size_t i = 1; i < hw; ++i) m_threads.emplace_back([this] { work(); });
    }
    ~Pool()
    {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_stop = true;
        }
        m_wake.notify_all();
        for (std::thread& t : m_threads) t.join();
    }

    // False when the pool is busy with another caller's run (the caller then runs serially).
    bool run(size_t count, const std::function<void(size_t)>& job)
    {
        std::unique_lock<std::mutex> runLock(m_runMutex, std::try_to_lock);
        if (!runLock.owns_lock() || m_threads.empty()) return false;
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_job = &job;
            m_count = count;
            m_next.store(1);
            m_done = 1;  // index 0: the caller's own
            ++m_generation;
        }
        m_wake.notify_all();
        job(0);
        drain();
        std::unique_lock<std::mutex> lock(m_mutex);
        m_finished.wait(lock, [&] { return m_done == m_count; });
        m_job = nullptr;
        return true;
    }

private:
    // Takes indices until none are left; counts each one done.
    void drain()
    {
        for (;;) {
            const size_t k = m_next.fetch_add(1);
            if (k >= m_count) return;
            (*m_job)(k);
            std::lock_guard<std::mutex> lock(m_mutex);
            if (++m_done == m_count) m_finished.notify_all();
        }
    }
    void work()
    {
        t_isWorker = true;
        unsigned long seen = 0;
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(m_mutex);
                m_wake.wait(lock, [&] { return m_stop || (m_generation != seen && m_job); });
                if (m_stop) return;
                seen = m_generation;
            }
            drain();
        }
    }

    std::vector<std::thread> m_threads;
    std::mutex m_runMutex;  // one run at a time
    std::mutex m_mutex;
    std::condition_variable m_wake, m_finished;
    const std::function<void(size_t)>* m_job = nullptr;
    size_t m_count = 0;
    std::atomic<size_t> m_next{0};
    size_t m_done = 0;
    unsigned long m_generation = 0;
    bool m_stop = false;
};

}  // namespace

void runOnPool(size_t count, const std::function<void(size_t)>& job)
{
    static Pool pool;
    if (count <= 1 || t_isWorker || !pool.run(count, job))
        for (size_t k = 0; k < count; ++k) job(k);
}

}  // namespace btgpu
