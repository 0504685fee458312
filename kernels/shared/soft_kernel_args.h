/* soft_kernel_args.h — solve_soft.cl's preamble: how its kernels share data between work-groups
 * on NVIDIA's GPUs, and the buffers and parameters its kernels and helpers pass along
 * (SOFT_ARGS / SOFT_PASS and the helpers' SOFT_FN_*). Included first, before any other header. */
#ifndef BTG_SOFT_KERNEL_ARGS_H
#define BTG_SOFT_KERNEL_ARGS_H

/* NVIDIA's GPUs (BTG_NVIDIA, from the host): the data the work-groups share in soft_resident is
 * not volatile but read with ld.global.cg (btgLoadShared4, btgLoadSharedInt, btgLoadSharedFloat:
 * L2, coherent across compute units, free to be issued together); every read of a body's rows,
 * another work-item's soft contact or a joint row's impulse goes through those. The H100's soft solve stage at 32,768 cubes:
 * 4.16 ms against 4.24 with volatile, the same state hash (2026-12-06). Plain loads, which may
 * hit a compute unit's stale L1, took 0.8 ms and changed the hash run to run: the stage's time
 * is its dependent loads' latency. The held pairs' support (soft_held_rows.h) stays volatile.
 * BTG_SOFT_VOLATILE=1 (a build option through BTGPU_CL_OPTIONS) keeps volatile, for measuring. */
#if defined(BTG_NVIDIA) && !defined(BTG_SOFT_VOLATILE)
#undef BTG_SHARED
#define BTG_SHARED
#define BTG_LOAD_CG 1
#define BTG_HELD_GLOBAL volatile __global
#endif
#define SOFT_BUFFERS __global BtgContact* contacts, __global BtgSoftContact* softContacts, \
    __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld, \
    __global const BtgFloat4* restrict linVel0, __global const BtgFloat4* restrict angVel0, \
    __global BtgFloat4* lin, __global BtgFloat4* ang, BTG_SHARED __global BtgFloat4* softBodies, \
    __global const BtgFloat4* restrict softSolver, \
    __global const BtgJoint* restrict joints, __global const BtgJointState* restrict jointState, \
    __global BtgJointRow* jointRows, __global const uint* restrict listStart, __global const uint* restrict listEntries, \
    __global const int* restrict slotOf, __global uint* counters, __global BtgRollingContact* rolling, \
    __global const uint* restrict contactManifolds, __global const BtgContactMaterial* restrict materials, int numMaterials, \
    __global const BtgFrictionDirs* restrict frictionDirs
#define SOFT_BUFFERS_PASS contacts, softContacts, props, invInertiaWorld, linVel0, angVel0, lin, ang, softBodies, softSolver, joints, \
    jointState, jointRows, listStart, listEntries, slotOf, counters, rolling, contactManifolds, materials, numMaterials, \
    frictionDirs
/* The kernels take the step's parameters by value (SOFT_ARGS). On CPU devices they hand the
 * helpers a pointer to them (SOFT_FN_ARGS; each helper copies them once, SOFT_FN_PARAMS): passed
 * by value to a helper that is not inlined, the struct was put together field by field and
 * copied at every call, and the copy's wide loads of the narrow stores just made stalled (7% of
 * a PoCL frame at cubes 8,000). A GPU's build passes them by value as before (copied into
 * registers at a helper's start they raised ptxas's spills). */
#define SOFT_ARGS SOFT_BUFFERS, BtgSoftParams params
#ifdef BTG_CPU_DEVICE
#define SOFT_FN_ARGS SOFT_BUFFERS, const BtgSoftParams* paramsIn
#define SOFT_PASS SOFT_BUFFERS_PASS, &params
#define SOFT_FN_PASS SOFT_BUFFERS_PASS, paramsIn
#define SOFT_FN_PARAMS const BtgSoftParams params = *paramsIn;
#else
#define SOFT_FN_ARGS SOFT_ARGS
#define SOFT_PASS SOFT_BUFFERS_PASS, params
#define SOFT_FN_PASS SOFT_PASS
#define SOFT_FN_PARAMS
#endif

#endif
