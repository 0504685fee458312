/* sync_bodies.cl — Stage: sync_in. Writes the rows the app changed between steps, and clears
 * the per-row timers of rows that take a new body.
 * Launch: one work-item per changed (or fresh) row. scatter_bodies reads rows, states (6 float4
 * per row: pos, rot, linVel, angVel, force, torque), rowProps and writes pos, rot, linVel,
 * angVel, extForce, extTorque, props at those rows; reset_rows (rows the app woke) writes
 * sleepTime, islandTime, sleepState, islandLabel at its rows and marks their islands in islandWake. */
#include "shared/types.h"

__kernel void scatter_bodies(int n, __global const int* restrict rows, __global const BtgFloat4* restrict states,
                             __global const BtgBodyProps* restrict rowProps, __global BtgFloat4* pos,
                             __global BtgFloat4* rot, __global BtgFloat4* linVel, __global BtgFloat4* angVel,
                             __global BtgFloat4* extForce, __global BtgFloat4* extTorque, __global BtgBodyProps* props)
{
    int k = get_global_id(0);
    if (k >= n) return;
    int r = rows[k];
    pos[r] = states[6 * k + 0];
    rot[r] = states[6 * k + 1];
    linVel[r] = states[6 * k + 2];
    angVel[r] = states[6 * k + 3];
    extForce[r] = states[6 * k + 4];
    extTorque[r] = states[6 * k + 5];
    props[r] = rowProps[k];
}

/* The app's own deactivation timers (Bullet's m_deactivationTime: activate() zeroes it, an app
 * may set it) for the rows whose timer it changed since the last readback. */
__kernel void set_sleep_times(int n, __global const int* restrict rows, __global const float* restrict times,
                              __global float* sleepTime)
{
    int k = get_global_id(0);
    if (k < n) sleepTime[rows[k]] = times[k];
}

/* A row that takes a new body starts as rebuild() starts every row: no time under the sleeping
 * thresholds, no island yet (+inf), awake. */
__kernel void reset_rows(int n, __global const int* restrict rows, __global float* sleepTime,
                         __global uint* islandTime, __global uint* sleepState, __global uint* islandLabel,
                         __global uint* islandWake, int numBodies, int woken)
{
    int k = get_global_id(0);
    if (k >= n) return;
    int r = rows[k];
    /* a sleeping body the app woke wakes its island before the next solve, as stock's (a fresh
       row, perhaps a retired one's, marks nothing) */
    const uint l = islandLabel[r];
    if (woken && l < (uint)numBodies) islandWake[l] = 1u;
    islandLabel[r] = (uint)r;
    sleepTime[r] = 0.0f;
    islandTime[r] = 0x7f800000u;
    sleepState[r] = 0u;
}
