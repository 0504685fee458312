// side_task.h — one job run on a thread of its own while the calling thread does other work:
// after a GPU step, Bullet's broadphase AABB sync (serial: Bullet's updateAabbs) beside the
// manifold fill (the worker pool), which touch disjoint data (gpu_world.cpp says when). The
// thread is started on first use and kept (starting one costs tens of microseconds a call).
#pragma once
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace btgpu {

class SideTask {
public:
    ~SideTask();
    // Runs job on the side thread; the previous job must have been waited for.
    void start(std::function<void()> job);
    // Until the job has finished (at once when none was started); rethrows what it threw.
    void wait();

private:
    void run();
    std::thread m_thread;
    std::mutex m_mutex;
    std::condition_variable m_cv;
    std::function<void()> m_job;
    bool m_pending = false;  // a job started and not finished
    std::exception_ptr m_error;
    bool m_quit = false;
};

}  // namespace btgpu
