/* group_append.h — a work-group's found pairs appended to a global list with one atomic for the
 * whole group, for CPU devices: their two cores' atomics on one shared counter, one a pair,
 * kept its cache line moving between them (perf on PoCL: 43% of leaves_sweep on that one
 * instruction). The pairs wait in local memory (a work-group runs on one core there) and go out
 * after a work-group barrier; past the buffer's room a pair is appended alone. Every pair is
 * counted, stored while it fits, as every append protocol here; the list's order is the atomics'
 * either way (the pair sort orders it). Device only; every work-item of the group must reach
 * btgGroupAppendBegin and btgGroupAppendEnd. */
#ifndef BTG_GROUP_APPEND_H
#define BTG_GROUP_APPEND_H
#include "types.h"

#define BTG_GROUP_APPEND_ROOM 256

static inline void btgGroupAppendBegin(__local uint* n, __local uint* extra)
{
    if (get_local_id(0) == 0) {
        *n = 0u;
        *extra = 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
}
static inline void btgGroupAppend(__local BtgPair* buf, __local uint* n, __global BtgPair* raw, volatile __global uint* counter,
                                  uint capacity, BtgPair q)
{
    const uint k = atomic_inc(n);
    if (k < BTG_GROUP_APPEND_ROOM) {
        buf[k] = q;
        return;
    }
    const uint slot = atomic_inc(counter);
    if (slot < capacity) raw[slot] = q;
}
/* The group's pairs out (one atomic), and `extra` (a count the group summed, e.g. m_newpairs'
 * share) added to *extraCounter where it is not zero. */
static inline void btgGroupAppendEnd(__local BtgPair* buf, __local uint* n, __local uint* base, __global BtgPair* raw,
                                     volatile __global uint* counter, uint capacity, __local uint* extra,
                                     volatile __global uint* extraCounter)
{
    barrier(CLK_LOCAL_MEM_FENCE);
    const uint m = min(*n, (uint)BTG_GROUP_APPEND_ROOM);
    if (get_local_id(0) == 0) {
        *base = m ? atomic_add(counter, m) : 0u;
        if (*extra) atomic_add(extraCounter, *extra);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint k = get_local_id(0); k < m; k += get_local_size(0))
        if (*base + k < capacity) raw[*base + k] = buf[k];
}
#endif
