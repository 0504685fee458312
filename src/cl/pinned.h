// pinned.h — host arrays in page-locked memory for the step's readback: a buffer allocated
// with CL_MEM_ALLOC_HOST_PTR and kept mapped, which drivers (NVIDIA's among them) copy into
// by DMA at full bus speed, where a read into ordinary pageable memory goes through a staging
// copy at a fraction of it. Host memory: not counted in the device total.
#pragma once
#include "cl/context.h"

#include <cstddef>

namespace btgpu::cl {

class PinnedBytes {
public:
    PinnedBytes() = default;
    ~PinnedBytes() { release(); }
    PinnedBytes(const PinnedBytes&) = delete;
    PinnedBytes& operator=(const PinnedBytes&) = delete;
    // Makes room for `bytes` (contents lost when it grows).
    void reserve(Context& ctx, size_t bytes);
    void release();
    void* data() const { return m_ptr; }

private:
    Context* m_ctx = nullptr;
    cl_mem m_mem = nullptr;
    void* m_ptr = nullptr;
    size_t m_bytes = 0;
};

template <typename T>
class PinnedArray {
public:
    void resize(Context& ctx, size_t n)
    {
        m_bytes.reserve(ctx, n * sizeof(T));
        m_size = n;
    }
    T* data() const { return static_cast<T*>(m_bytes.data()); }
    size_t size() const { return m_size; }
    T& operator[](size_t i) const { return data()[i]; }
    void release()
    {
        m_bytes.release();
        m_size = 0;
    }

private:
    PinnedBytes m_bytes;
    size_t m_size = 0;
};

}  // namespace btgpu::cl
