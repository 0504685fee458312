// launch.cpp — enqueueing and profiling-event bookkeeping.
#include "cl/launch.h"

#include <algorithm>
#include <cstdlib>

namespace btgpu::cl {

void Profiler::add(cl_event e, cl_kernel kernel)
{
    static const bool perKernel = [] {
        const char* v = std::getenv("BTGPU_PROFILE_KERNELS");
        return v && v[0] == '1';
    }();
    if (!perKernel || !kernel) {
        m_events.emplace_back(stage, e);
        return;
    }
    char name[128] = {0};
    if (clGetKernelInfo(kernel, CL_KERNEL_FUNCTION_NAME, sizeof(name) - 1, name, nullptr) != CL_SUCCESS) name[0] = 0;
    m_events.emplace_back(stage + ": " + name, e);
}

void Profiler::collect(std::map<std::string, double>& out)
{
    for (auto& se : m_events) {
        cl_ulong t0 = 0, t1 = 0;
        if (clWaitForEvents(1, &se.second) == CL_SUCCESS &&
            clGetEventProfilingInfo(se.second, CL_PROFILING_COMMAND_START, sizeof(t0), &t0, nullptr) == CL_SUCCESS &&
            clGetEventProfilingInfo(se.second, CL_PROFILING_COMMAND_END, sizeof(t1), &t1, nullptr) == CL_SUCCESS)
            out[se.first] += double(t1 - t0) * 1e-6;
        clReleaseEvent(se.second);
    }
    m_events.clear();
}

void Launch::run(size_t global, size_t localSize)
{
    if (global == 0) return;
    size_t maxLocal = m_ctx.device().maxWorkGroupSize;
    if (localSize > maxLocal) localSize = maxLocal;
    size_t g = (global + localSize - 1) / localSize * localSize;
    cl_event ev = nullptr;
    bool keep = m_prof && m_prof->enabled;
    BTGPU_CL_CHECK(clEnqueueNDRangeKernel(m_ctx.queue(), m_kernel, 1, nullptr, &g, &localSize, 0, nullptr, keep ? &ev : nullptr));
    if (m_prof) m_prof->countLaunch();
    if (keep) m_prof->add(ev, m_kernel);
}

size_t kernelGroupLimit(Context& ctx, cl_kernel kernel)
{
    size_t limit = 0;
    cl_device_id device = ctx.device().device;
    BTGPU_CL_CHECK(clGetKernelWorkGroupInfo(kernel, device, CL_KERNEL_WORK_GROUP_SIZE, sizeof(limit), &limit, nullptr));
    return std::max<size_t>(1, std::min(limit, ctx.device().maxWorkGroupSize));
}

}  // namespace btgpu::cl
