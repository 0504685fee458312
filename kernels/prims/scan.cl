/* scan.cl — exclusive prefix sum of uint (wrapping), in place.
 * Stage: primitive (used by radix_sort and by stages that compact lists).
 * Launch: scan_blocks, one work-item per element, work-groups of a power-of-two size L with
 * L uints of local memory; scan_add_offsets, one work-item per element, same L.
 * Reads/Writes: data (n elements); scan_blocks writes each block's total to blockSums, which
 * the host scans recursively and scan_add_offsets adds back. Integer only: deterministic. */

__kernel void scan_blocks(__global uint* restrict data, __global uint* restrict blockSums, uint n,
                          __local uint* tmp)
{
    uint gid = get_global_id(0);
    uint lid = get_local_id(0);
    uint size = get_local_size(0);
    uint x = gid < n ? data[gid] : 0u;
    tmp[lid] = x;
    barrier(CLK_LOCAL_MEM_FENCE);
    /* Hillis-Steele: log2(L) steps; each step reads before any item writes (two barriers). */
    for (uint offset = 1; offset < size; offset <<= 1) {
        uint add = lid >= offset ? tmp[lid - offset] : 0u;
        barrier(CLK_LOCAL_MEM_FENCE);
        tmp[lid] += add;
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (gid < n) data[gid] = tmp[lid] - x;
    if (lid == size - 1) blockSums[get_group_id(0)] = tmp[lid];
}

__kernel void scan_add_offsets(__global uint* restrict data, __global const uint* restrict blockOffsets, uint n)
{
    uint gid = get_global_id(0);
    if (gid >= n) return;
    data[gid] += blockOffsets[get_group_id(0)];
}
