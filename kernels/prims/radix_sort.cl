/* radix_sort.cl — one pass of a stable LSD radix sort of uint keys with uint values, 4 bits
 * per pass. Each work-item owns a contiguous chunk and walks it in order, so the scatter is
 * stable and deterministic without local-memory ranking (simple; not bandwidth-optimal).
 * Stage: primitive. Launch: one work-item per chunk of `chunk` elements (both kernels).
 * Reads: keysIn, valsIn, hist (digit-major, exclusively scanned between the two kernels).
 * Writes: radix_histogram: hist[d * numChunks + c]; radix_scatter: keysOut, valsOut. */

#define BTG_RADIX 16u
#define BTG_RADIX_MASK 15u

__kernel void radix_histogram(__global const uint* restrict keys, __global uint* restrict hist, uint n,
                              uint shift, uint chunk, uint numChunks)
{
    uint c = get_global_id(0);
    if (c >= numChunks) return;
    uint counts[BTG_RADIX];
    for (uint d = 0; d < BTG_RADIX; ++d) counts[d] = 0u;
    uint begin = c * chunk;
    uint end = min(begin + chunk, n);
    for (uint i = begin; i < end; ++i) counts[(keys[i] >> shift) & BTG_RADIX_MASK]++;
    for (uint d = 0; d < BTG_RADIX; ++d) hist[d * numChunks + c] = counts[d];
}

__kernel void radix_scatter(__global const uint* restrict keysIn, __global const uint* restrict valsIn,
                            __global uint* restrict keysOut, __global uint* restrict valsOut,
                            __global const uint* restrict hist, uint n, uint shift, uint chunk,
                            uint numChunks)
{
    uint c = get_global_id(0);
    if (c >= numChunks) return;
    uint offsets[BTG_RADIX];
    for (uint d = 0; d < BTG_RADIX; ++d) offsets[d] = hist[d * numChunks + c];
    uint begin = c * chunk;
    uint end = min(begin + chunk, n);
    for (uint i = begin; i < end; ++i) {
        uint k = keysIn[i];
        uint o = offsets[(k >> shift) & BTG_RADIX_MASK]++;
        keysOut[o] = k;
        valsOut[o] = valsIn[i];
    }
}
