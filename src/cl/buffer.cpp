// buffer.cpp — buffer allocation and the per-context byte count.
#include "cl/buffer.h"

#include <map>
#include <mutex>

namespace btgpu::cl {

namespace {
std::mutex g_mutex;
std::map<const Context*, size_t>& totals()
{
    static std::map<const Context*, size_t> t;
    return t;
}
}  // namespace

size_t bytesInUse(const Context& ctx)
{
    std::lock_guard<std::mutex> lock(g_mutex);
    auto it = totals().find(&ctx);
    return it == totals().end() ? 0 : it->second;
}

Buffer& Buffer::operator=(Buffer&& o) noexcept
{
    if (this != &o) {
        release();
        m_mem = o.m_mem;
        m_bytes = o.m_bytes;
        m_ctx = o.m_ctx;
        o.m_mem = nullptr;
        o.m_bytes = 0;
        o.m_ctx = nullptr;
    }
    return *this;
}

void Buffer::allocate(Context& ctx, size_t bytes)
{
    release();
    cl_int err = CL_SUCCESS;
    // Never a zero-size buffer: OpenCL rejects it, and an empty column is still bound.
    size_t n = bytes ? bytes : 16;
    if (ctx.memoryLimit() && bytesInUse(ctx) + n > ctx.memoryLimit())
        fail(("clCreateBuffer(" + std::to_string(n) + " bytes, over the device memory limit of " +
              std::to_string(ctx.memoryLimit()) + " bytes)")
                 .c_str(),
             CL_MEM_OBJECT_ALLOCATION_FAILURE, __FILE__, __LINE__);
    m_mem = clCreateBuffer(ctx.context(), CL_MEM_READ_WRITE, n, nullptr, &err);
    if (err != CL_SUCCESS) fail(("clCreateBuffer(" + std::to_string(n) + " bytes)").c_str(), err, __FILE__, __LINE__);
    m_bytes = n;
    m_ctx = &ctx;
    std::lock_guard<std::mutex> lock(g_mutex);
    totals()[m_ctx] += m_bytes;
}

void Buffer::release()
{
    if (!m_mem) return;
    clReleaseMemObject(m_mem);
    {
        std::lock_guard<std::mutex> lock(g_mutex);
        totals()[m_ctx] -= m_bytes;
    }
    m_mem = nullptr;
    m_bytes = 0;
    m_ctx = nullptr;
}

}  // namespace btgpu::cl
