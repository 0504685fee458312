/* wide_chunks.h — the chunks of eight slots that a CPU device's wide sweeps take (soft_wide.h,
 * pgs_wide.h): the regular colours' slots of the colour order in chunks of eight, colour c's
 * chunk m holding slots colorStart[c] + 8m.. and sitting at wideStart[c] + m (a colour's last
 * chunk may be part empty). Shared by solve_soft.cl's and solve_constraints.cl's wide passes. */
#ifndef BTG_WIDE_CHUNKS_H
#define BTG_WIDE_CHUNKS_H
#include "soft_rows.h" /* BTG_SOFT_WIDE: the lanes of a chunk */

/* Each regular colour's first chunk, and their total at wideStart[numColors - 1] (one work-item). */
static void btgWideOffsets(__global const uint* restrict colorStart, __global uint* wideStart, int numColors)
{
    uint sum = 0u;
    for (int c = 0; c < numColors - 1; ++c) {
        wideStart[c] = sum;
        sum += (colorStart[c + 1] - colorStart[c] + BTG_SOFT_WIDE - 1) / BTG_SOFT_WIDE;
    }
    wideStart[max(numColors - 1, 0)] = sum;
}
/* The colour of slot k (k in a regular colour). */
static int btgWideColorOf(int k, __global const uint* restrict colorStart)
{
    int c = 0;
    while (colorStart[c + 1] <= (uint)k) ++c;
    return c;
}
/* Slot k's chunk and lane. */
static int2 btgWideChunkOf(int k, __global const uint* restrict colorStart, __global const uint* restrict wideStart)
{
    const int c = btgWideColorOf(k, colorStart);
    const int at = k - (int)colorStart[c];
    return (int2)((int)wideStart[c] + at / BTG_SOFT_WIDE, at % BTG_SOFT_WIDE);
}
/* Whether slot k is its colour's last (it then empties the rest of its chunk). */
static int btgWideLastOfColor(int k, __global const uint* restrict colorStart)
{
    return k + 1 == (int)colorStart[btgWideColorOf(k, colorStart) + 1];
}
/* Work-item `item` of `items`' run of consecutive chunks of a colour of `chunks`: [x, y). */
static int2 btgWideRun(int chunks, int item, int items)
{
    const int per = (chunks + items - 1) / items;
    const int first = item * per;
    return (int2)(first, min(chunks, first + per));
}
#endif
