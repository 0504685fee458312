/* grid_barrier.h — a barrier across all work-groups of one launch, for the "resident" kernels
 * (batching, solve) that run every round of a stage in one launch on GPUs instead of one
 * launch per round: a launch costs a few microseconds on a GPU, and these stages have hundreds
 * of rounds a step. Valid only when every group of the launch is resident at once: the host
 * launches at most one group per compute unit. Should a group never arrive (a device that does
 * not keep them all resident), the waiters give up after spinLimit polls, set timedOut and
 * every group returns; the kernel reports BTG_STATUS_GRID_BARRIER_TIMEOUT and the host redoes
 * the step with per-round launches. The barrier word is left ready for the next launch after a
 * normal exit (the arrival count returns to zero; waiters compare generations for change
 * only), so the host zeroes it once, when it is allocated. Device code only. */
#ifndef BTG_GRID_BARRIER_H
#define BTG_GRID_BARRIER_H
#include "prelude.h"

/* Each word on a line of its own (128 bytes apart): the waiters' polls of the generation then do
 * not contend with the arrivals' atomics, and a poll reads one line. */
typedef struct {
    uint arrived;    /* groups at the barrier in this generation */
    uint pad0[31];
    uint generation; /* bumped by the last arrival */
    uint pad1[31];
    uint timedOut;   /* set by a waiter that gave up */
    uint pad2[31];
} BtgGridBarrier;

/* words the host allocates (and zeroes) for one barrier */
#define BTG_GRID_BARRIER_WORDS 96

#ifdef __OPENCL_C_VERSION__
/* Qualifier of data the resident kernels share between work-groups: the host builds with
 * -DBTG_SHARED=volatile on GPUs (per-compute-unit caches are not coherent) and empty on CPUs
 * (coherent caches; volatile there only stops vectorization). */
#ifndef BTG_SHARED
#define BTG_SHARED volatile
#endif

/* A float4 (an int, a float) another work-group wrote in this launch, read through a BTG_SHARED pointer.
 * Plain (volatile on GPUs) by default. With BTG_LOAD_CG (NVIDIA only: solve_soft.cl sets it on
 * NVIDIA's GPUs, where it also drops volatile from BTG_SHARED; for other programs a build option
 * through BTGPU_CL_OPTIONS) it is read with PTX's ld.global.cg, cached in L2 only: coherent
 * across compute units, as volatile is, but free to be issued beside other loads (on the H100
 * the soft solve 2% faster than with volatile). A program that drops volatile must read every
 * such datum through these: a plain load may hit a compute unit's stale L1. */
#if defined(BTG_LOAD_CG)
static inline float4 btgLoadShared4(BTG_SHARED __global const float4* p)
{
    float4 v;
    __asm__ __volatile__("ld.global.cg.v4.f32 {%0, %1, %2, %3}, [%4];"
                 : "=f"(v.x), "=f"(v.y), "=f"(v.z), "=f"(v.w)
                 : "l"((__global const float4*)p));
    return v;
}
static inline int btgLoadSharedInt(BTG_SHARED __global const int* p)
{
    int v;
    __asm__ __volatile__("ld.global.cg.s32 %0, [%1];" : "=r"(v) : "l"((__global const int*)p));
    return v;
}
static inline float btgLoadSharedFloat(BTG_SHARED __global const float* p)
{
    float v;
    __asm__ __volatile__("ld.global.cg.f32 %0, [%1];" : "=f"(v) : "l"((__global const float*)p));
    return v;
}
#else
#define btgLoadShared4(p) (*(p))
#define btgLoadSharedInt(p) (*(p))
#define btgLoadSharedFloat(p) (*(p))
#endif

/* Returns nonzero when the launch must stop (a timeout). Call from every work-item. Global
 * writes before it are visible to every group after it for data read through BTG_SHARED
 * pointers or written by atomics. */
static int btgGridBarrier(volatile __global BtgGridBarrier* bar, int spinLimit, __local int* quit)
{
    const uint groups = (uint)get_num_groups(0);
    barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE);
    if (groups == 1u) return 0; /* one group: the local barrier is the whole barrier */
    if (get_local_id(0) == 0) {
        mem_fence(CLK_GLOBAL_MEM_FENCE);
        uint gen = bar->generation;
        int stop = 0;
        if (atomic_inc(&bar->arrived) == groups - 1u) {
            bar->arrived = 0u;
            mem_fence(CLK_GLOBAL_MEM_FENCE);
            atomic_inc(&bar->generation);
        } else {
            /* the give-up flag is read once every 64 polls: it is for a broken device, and each
             * read is another L2 round trip on the waiters' path */
            int spins = 0;
            while (bar->generation == gen) {
                if ((++spins & 63) == 0) {
                    if (bar->timedOut != 0u) { stop = 1; break; }
                    if (spins > spinLimit) { atomic_xchg(&bar->timedOut, 1u); stop = 1; break; }
                }
            }
        }
        mem_fence(CLK_GLOBAL_MEM_FENCE);
        *quit = stop;
    }
    barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE);
    return *quit;
}

/* A grid barrier whose arrival count only grows within the launch: barrier n (phase counts them
 * from 1, work-item 0's own count) waits until `arrived` reaches groups x n. One atomic and polls
 * of one word a barrier, where btgGridBarrier's last arrival also resets the count and bumps the
 * generation: on the H100 a barrier alone 0.58 us against 0.81 (2026-12-05 probe). The host
 * zeroes the words before every launch that uses it (and gives it its own words: btgGridBarrier
 * needs `arrived` at zero). Same return and visibility as btgGridBarrier. */
static int btgGridBarrierCounting(volatile __global BtgGridBarrier* bar, uint* phase, int spinLimit, __local int* quit)
{
    const uint groups = (uint)get_num_groups(0);
    barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE);
    if (groups == 1u) return 0; /* one group: the local barrier is the whole barrier */
    if (get_local_id(0) == 0) {
        const uint want = groups * ++*phase;
        mem_fence(CLK_GLOBAL_MEM_FENCE);
        int stop = 0;
        if (atomic_inc(&bar->arrived) + 1u != want) {
            int spins = 0;
            while (bar->arrived < want) {
                if ((++spins & 63) == 0) {
                    if (bar->timedOut != 0u) { stop = 1; break; }
                    if (spins > spinLimit) { atomic_xchg(&bar->timedOut, 1u); stop = 1; break; }
                }
            }
        }
        mem_fence(CLK_GLOBAL_MEM_FENCE);
        *quit = stop;
    }
    barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE);
    return *quit;
}

/* The resident solves' flows (solve_soft.cl, solve_constraints.cl): one work-item waits until a
 * count another work-item moves on reaches `want`. Returns nonzero when it gave up, as the
 * barrier's waiters do (past spinLimit polls, or another waiter gave up). */
static int btgWaitForCount(volatile __global uint* count, uint want, volatile __global BtgGridBarrier* bar,
                           int spinLimit)
{
    int spins = 0;
    while (*count != want) {
        if ((++spins & 63) == 0) {
            if (bar->timedOut != 0u) return 1;
            if (spins > spinLimit) {
                atomic_xchg(&bar->timedOut, 1u);
                return 1;
            }
        }
    }
    return 0;
}
#endif

#endif
