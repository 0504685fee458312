// pinned.cpp — the mapped host-visible buffer behind PinnedArray.
#include "cl/pinned.h"

#include "cl/error.h"

#include <string>

namespace btgpu::cl {

void PinnedBytes::reserve(Context& ctx, size_t bytes)
{
    if (bytes <= m_bytes && m_mem) return;
    release();
    size_t n = bytes ? bytes : 16;
    cl_int err = CL_SUCCESS;
    m_mem = clCreateBuffer(ctx.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, n, nullptr, &err);
    if (err != CL_SUCCESS) fail(("clCreateBuffer(ALLOC_HOST_PTR, " + std::to_string(n) + " bytes)").c_str(), err, __FILE__, __LINE__);
    m_ctx = &ctx;
    m_bytes = n;
    m_ptr = clEnqueueMapBuffer(ctx.queue(), m_mem, CL_TRUE, CL_MAP_READ | CL_MAP_WRITE, 0, n, 0, nullptr, nullptr, &err);
    if (err != CL_SUCCESS) {
        clReleaseMemObject(m_mem);
        m_mem = nullptr;
        m_bytes = 0;
        fail("clEnqueueMapBuffer(readback)", err, __FILE__, __LINE__);
    }
}

void PinnedBytes::release()
{
    if (!m_mem) return;
    // Unmap before release; errors here have nowhere to go (destructors must not throw).
    clEnqueueUnmapMemObject(m_ctx->queue(), m_mem, m_ptr, 0, nullptr, nullptr);
    clFinish(m_ctx->queue());
    clReleaseMemObject(m_mem);
    m_mem = nullptr;
    m_ptr = nullptr;
    m_bytes = 0;
}

}  // namespace btgpu::cl
