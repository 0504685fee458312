// buffer.h — RAII device buffers. DeviceArray<T> is a typed column that grows on demand
// (geometrically, optionally keeping its contents) and counts its bytes in the context's
// memory total, so the Report can say how much device memory the scene uses.
#pragma once
#include "cl/context.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace btgpu::cl {

class Buffer {
public:
    Buffer() = default;
    ~Buffer() { release(); }
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    Buffer(Buffer&& o) noexcept { *this = std::move(o); }
    Buffer& operator=(Buffer&& o) noexcept;

    // Replaces the buffer by one of `bytes` (contents lost).
    void allocate(Context& ctx, size_t bytes);
    void release();
    cl_mem mem() const { return m_mem; }
    size_t bytes() const { return m_bytes; }

private:
    cl_mem m_mem = nullptr;
    size_t m_bytes = 0;
    Context* m_ctx = nullptr;
};

template <typename T>
class DeviceArray {
public:
    // Makes room for at least n elements. A first allocation takes exactly n (a column sized
    // once for N bodies wastes nothing); a later growth takes at least 1.5x, so repeated growth
    // stays cheap. When preserve is set the old contents are copied on the device.
    void reserve(Context& ctx, size_t n, bool preserve = false)
    {
        if (n <= m_capacity && m_buf.mem()) return;
        size_t grown = m_capacity ? m_capacity + m_capacity / 2 + 16 : 0;
        grow(ctx, std::max(n, grown), preserve);
    }
    // Exactly n elements when it must grow: for the columns whose capacity the caller already
    // grows geometrically (pairCapacity, contactCapacity), which 1.5x on top would waste.
    void reserveExact(Context& ctx, size_t n, bool preserve = false)
    {
        if (n <= m_capacity && m_buf.mem()) return;
        grow(ctx, n, preserve);
    }
    void upload(Context& ctx, const T* data, size_t n, size_t offset = 0)
    {
        if (n == 0) return;
        reserve(ctx, offset + n, offset != 0);
        BTGPU_CL_CHECK(clEnqueueWriteBuffer(ctx.queue(), m_buf.mem(), CL_TRUE, offset * sizeof(T), n * sizeof(T), data, 0, nullptr, nullptr));
    }
    void upload(Context& ctx, const std::vector<T>& v) { upload(ctx, v.data(), v.size()); }
    void download(Context& ctx, T* data, size_t n, size_t offset = 0) const
    {
        if (n == 0) return;
        BTGPU_CL_CHECK(clEnqueueReadBuffer(ctx.queue(), m_buf.mem(), CL_TRUE, offset * sizeof(T), n * sizeof(T), data, 0, nullptr, nullptr));
    }
    std::vector<T> download(Context& ctx, size_t n) const
    {
        std::vector<T> v(n);
        download(ctx, v.data(), n);
        return v;
    }
    // Sets the first n elements to a byte pattern of zero.
    void zero(Context& ctx, size_t n)
    {
        if (n == 0) return;
        reserve(ctx, n, true);
        T z{};
        BTGPU_CL_CHECK(clEnqueueFillBuffer(ctx.queue(), m_buf.mem(), &z, sizeof(T) <= 128 && (sizeof(T) & (sizeof(T) - 1)) == 0 ? sizeof(T) : 4, 0, n * sizeof(T), 0, nullptr, nullptr));
    }
    // Sets elements [first, first + count) to `value` (T of 4 bytes or a power of two up to 128).
    void fill(Context& ctx, const T& value, size_t first, size_t count)
    {
        if (count == 0) return;
        static_assert(sizeof(T) <= 128 && (sizeof(T) & (sizeof(T) - 1)) == 0, "fill needs a power-of-two size");
        BTGPU_CL_CHECK(clEnqueueFillBuffer(ctx.queue(), m_buf.mem(), &value, sizeof(T), first * sizeof(T),
                                           count * sizeof(T), 0, nullptr, nullptr));
    }
    // Copies src's first n elements over this array's first n, which must both hold them
    // (never reallocates: a column that must keep its size and contents).
    void copyRangeFrom(Context& ctx, const DeviceArray<T>& src, size_t n)
    {
        if (n == 0) return;
        BTGPU_CL_CHECK(clEnqueueCopyBuffer(ctx.queue(), src.mem(), m_buf.mem(), 0, 0, n * sizeof(T), 0, nullptr, nullptr));
    }
    // Queues a read of n elements from offset into host memory, without waiting (Context::finish
    // waits for all; *done, when given, is an event of this read alone, the caller's to release).
    void readAsync(Context& ctx, T* data, size_t n, size_t offset = 0, cl_event* done = nullptr) const
    {
        if (n == 0) return;
        BTGPU_CL_CHECK(clEnqueueReadBuffer(ctx.queue(), m_buf.mem(), CL_FALSE, offset * sizeof(T), n * sizeof(T), data, 0,
                                           nullptr, done));
    }
    void copyFrom(Context& ctx, const DeviceArray<T>& src, size_t n)
    {
        if (n == 0) return;
        reserve(ctx, n);
        BTGPU_CL_CHECK(clEnqueueCopyBuffer(ctx.queue(), src.mem(), m_buf.mem(), 0, 0, n * sizeof(T), 0, nullptr, nullptr));
    }
    void release()
    {
        m_buf.release();
        m_capacity = 0;
    }
    cl_mem mem() const { return m_buf.mem(); }
    size_t capacity() const { return m_capacity; }
    size_t bytes() const { return m_buf.bytes(); }

private:
    void grow(Context& ctx, size_t cap, bool preserve)
    {
        cap = std::max<size_t>(cap, 1);
        Buffer fresh;
        fresh.allocate(ctx, cap * sizeof(T));
        if (preserve && m_buf.mem() && m_capacity)
            BTGPU_CL_CHECK(clEnqueueCopyBuffer(ctx.queue(), m_buf.mem(), fresh.mem(), 0, 0, m_capacity * sizeof(T), 0, nullptr, nullptr));
        m_buf = std::move(fresh);
        m_capacity = cap;
    }

    Buffer m_buf;
    size_t m_capacity = 0;
};

// A typed window on an array's storage, holding no bytes of its own: a column that lives only
// while the array under it is dead (the soft step's rows hold the new warm-start cache and then
// the contact reports after its solve: SolverScratch::rowsAs). Taken afresh where it is used:
// the array may be reallocated between uses.
template <typename T>
class ArrayView {
public:
    ArrayView() = default;
    explicit ArrayView(const DeviceArray<T>& a) : m_mem(a.mem()), m_capacity(a.capacity()) {}
    // U's storage seen as n T's (fewer where its bytes hold fewer).
    template <typename U>
    static ArrayView over(const DeviceArray<U>& a, size_t n)
    {
        ArrayView v;
        v.m_mem = a.mem();
        v.m_capacity = a.mem() ? std::min(n, a.capacity() * sizeof(U) / sizeof(T)) : 0;
        return v;
    }
    cl_mem mem() const { return m_mem; }
    size_t capacity() const { return m_capacity; }
    void upload(Context& ctx, const std::vector<T>& v) const
    {
        if (!v.empty())
            BTGPU_CL_CHECK(clEnqueueWriteBuffer(ctx.queue(), m_mem, CL_TRUE, 0, v.size() * sizeof(T), v.data(), 0, nullptr, nullptr));
    }
    void readAsync(Context& ctx, T* data, size_t n, size_t offset = 0) const
    {
        if (n == 0) return;
        BTGPU_CL_CHECK(clEnqueueReadBuffer(ctx.queue(), m_mem, CL_FALSE, offset * sizeof(T), n * sizeof(T), data, 0,
                                           nullptr, nullptr));
    }
    std::vector<T> download(Context& ctx, size_t n) const
    {
        std::vector<T> v(n);
        if (n) BTGPU_CL_CHECK(clEnqueueReadBuffer(ctx.queue(), m_mem, CL_TRUE, 0, n * sizeof(T), v.data(), 0, nullptr, nullptr));
        return v;
    }

private:
    cl_mem m_mem = nullptr;
    size_t m_capacity = 0;
};

// Total bytes of all live Buffers per context (device memory in use).
size_t bytesInUse(const Context& ctx);

}  // namespace btgpu::cl
