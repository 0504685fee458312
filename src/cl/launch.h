// launch.h — binds kernel arguments in order and enqueues; with profiling on, each launch's
// event is kept under the current stage name so the Report can give per-stage device times.
#pragma once
#include "cl/buffer.h"
#include "cl/program.h"

#include <map>
#include <string>
#include <vector>

namespace btgpu::cl {

// Collects launch events by stage; one per world.
class Profiler {
public:
    bool enabled = false;
    std::string stage = "other";
    // BTGPU_PROFILE_KERNELS=1 (for measuring): each launch under "stage: kernel" instead.
    void add(cl_event e, cl_kernel kernel = nullptr);
    // Waits for the kept events and adds their device milliseconds per stage to `out`.
    void collect(std::map<std::string, double>& out);
    int launches() const { return m_launches; }
    void resetLaunchCount() { m_launches = 0; }
    void countLaunch() { ++m_launches; }

private:
    std::vector<std::pair<std::string, cl_event>> m_events;
    int m_launches = 0;
};

class Launch {
public:
    Launch(Context& ctx, cl_kernel kernel, Profiler* profiler = nullptr) : m_ctx(ctx), m_kernel(kernel), m_prof(profiler) {}
    template <typename T>
    Launch& arg(const T& value)
    {
        BTGPU_CL_CHECK(clSetKernelArg(m_kernel, m_index++, sizeof(T), &value));
        return *this;
    }
    template <typename T>
    Launch& arg(const DeviceArray<T>& a)
    {
        cl_mem m = a.mem();
        BTGPU_CL_CHECK(clSetKernelArg(m_kernel, m_index++, sizeof(cl_mem), &m));
        return *this;
    }
    template <typename T>
    Launch& arg(const ArrayView<T>& a)
    {
        cl_mem m = a.mem();
        BTGPU_CL_CHECK(clSetKernelArg(m_kernel, m_index++, sizeof(cl_mem), &m));
        return *this;
    }
    Launch& local(size_t bytes)
    {
        BTGPU_CL_CHECK(clSetKernelArg(m_kernel, m_index++, bytes, nullptr));
        return *this;
    }
    // One work-item per element: global is rounded up to a multiple of the group size; the
    // kernel early-outs on its own count. global 0 launches nothing.
    void run(size_t global, size_t localSize = 64);

private:
    Context& m_ctx;
    cl_kernel m_kernel;
    Profiler* m_prof;
    cl_uint m_index = 0;
};

// The largest work-group this kernel can run with on the context's device (its registers and
// local memory may allow less than the device maximum).
size_t kernelGroupLimit(Context& ctx, cl_kernel kernel);

}  // namespace btgpu::cl
