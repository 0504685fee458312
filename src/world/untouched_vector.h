// untouched_vector.h — a std::vector whose resize leaves new elements default-initialised (for
// plain data: not written), so a large host array of per-body rows can be sized at once and
// then written in parallel chunks, each thread touching (and page-faulting) its own part. A
// plain vector's resize writes every new element on the calling thread first: at 1,000,000
// bodies the rebuild's row arrays were sized in 0.7 s of page faults on one core.
#pragma once
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace btgpu {

template <typename T, typename A = std::allocator<T>>
class DefaultInitAllocator : public A {
    using Traits = std::allocator_traits<A>;

public:
    template <typename U>
    struct rebind {
        using other = DefaultInitAllocator<U, typename Traits::template rebind_alloc<U>>;
    };
    using A::A;
    DefaultInitAllocator() = default;
    template <typename U, typename B>
    DefaultInitAllocator(const DefaultInitAllocator<U, B>& o) noexcept : A(o) {}

    template <typename U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
    {
        ::new (static_cast<void*>(p)) U;  // default-initialised: plain data left unwritten
    }
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args)
    {
        Traits::construct(static_cast<A&>(*this), p, std::forward<Args>(args)...);
    }
};

template <typename T>
using UntouchedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace btgpu
