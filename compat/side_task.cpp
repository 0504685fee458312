// side_task.cpp — see side_task.h.
#include "side_task.h"

#include <utility>

namespace btgpu {

SideTask::~SideTask()
{
    if (!m_thread.joinable()) return;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_quit = true;
    }
    m_cv.notify_all();
    m_thread.join();
}

void SideTask::start(std::function<void()> job)
{
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_job = std::move(job);
        m_pending = true;
    }
    if (!m_thread.joinable()) m_thread = std::thread([this] { run(); });
    m_cv.notify_all();
}

void SideTask::wait()
{
    std::unique_lock<std::mutex> lock(m_mutex);
    m_cv.wait(lock, [this] { return !m_pending; });
    if (m_error) std::rethrow_exception(std::exchange(m_error, nullptr));
}

void SideTask::run()
{
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        m_cv.wait(lock, [this] { return m_quit || (m_pending && m_job); });
        if (m_quit) return;
        std::function<void()> job = std::move(m_job);
        m_job = nullptr;
        lock.unlock();
        std::exception_ptr error;
        try {
            job();
        } catch (...) {
            error = std::current_exception();  // for wait(): one escaping this thread would end the app
        }
        lock.lock();
        m_error = error;
        m_pending = false;
        m_cv.notify_all();
    }
}

}  // namespace btgpu
