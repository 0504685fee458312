/* radix_sort.cl — one pass of a stable LSD radix sort of uint keys with uint values, 4 bits
 * per pass, two ways. The chunk kernels (CPU devices): each work-item owns a contiguous chunk
 * and walks it in order, so the scatter is stable and deterministic without local-memory
 * ranking. The tile kernels (GPUs), below.
 * Stage: primitive. Launch: one work-item per chunk of `chunk` elements (both kernels).
 * Reads: keysIn, valsIn, hist (digit-major, exclusively scanned between the two kernels).
 * Writes: radix_histogram: hist[d * numChunks + c]; radix_scatter: keysOut, valsOut. */

#define BTG_RADIX 16u
#define BTG_RADIX_MASK 15u
/* the ping-pong of two pointers (of either address space) between passes */
#define BTG_RADIX_SWAP(T, a, b) \
    do {                        \
        T swapped_ = (a);       \
        (a) = (b);              \
        (b) = swapped_;         \
    } while (0)

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

/* The tiled passes (GPUs; RadixScratch's host side picks them): a work-group of
 * BTG_RADIX_GROUP work-items takes a tile of BTG_RADIX_TILE consecutive keys, read coalesced;
 * the chunk kernels above give each work-item 64 keys of its own, a strided walk that left a
 * GPU's loads uncoalesced and its compute units nearly idle (H100, cubes 32,768: the pair sort's
 * passes about 0.4 ms a step). A pass is radix_tile_count (each tile's digit counts,
 * digit-major), radix_tile_offsets (one work-group: their exclusive scan, in place; left out
 * up to 512 tiles, radix_tile_scatter then adds them up itself) and radix_tile_scatter
 * (each key's place: its digit's offset for the tile plus its rank among the tile's keys of that
 * digit before it, from a scan of per-work-item counts in local memory).
 * Stable: a tile's keys keep their order within a digit, and tiles come in order. */
#define BTG_RADIX_GROUP 256u
#define BTG_RADIX_PER_ITEM 4u
#define BTG_RADIX_TILE (BTG_RADIX_GROUP * BTG_RADIX_PER_ITEM)

/* Work-group exclusive scan of one uint a work-item (BTG_RADIX_GROUP of them) in `sums`;
 * returns this work-item's prefix. Hillis-Steele in place. */
static uint radix_group_scan(__local uint* sums, uint l, uint v)
{
    sums[l] = v;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint d = 1u; d < BTG_RADIX_GROUP; d <<= 1) {
        const uint add = l >= d ? sums[l - d] : 0u;
        barrier(CLK_LOCAL_MEM_FENCE);
        sums[l] += add;
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    const uint inclusive = sums[l];
    barrier(CLK_LOCAL_MEM_FENCE);
    return inclusive - v;
}

/* Each key's rank in the tile, less its rank among its own work-item's keys of that digit
 * (ushort: at most a tile's 1,024, and radix_tile_sort's local memory stays under the 32 KB
 * every OpenCL device offers): rank[d * BTG_RADIX_GROUP + l] becomes the number of the tile's
 * keys of a smaller digit, plus those of digit d held by work-items before l (work-item l holds
 * the tile's keys [4 l, 4 l + 4), of which the first `valid` of the tile count). */
static void radix_tile_ranks(__local ushort* rank, __local uint* sums, __local const uint* tileKeys, uint valid,
                             uint shift)
{
    const uint l = (uint)get_local_id(0), first = l * BTG_RADIX_PER_ITEM;
    for (uint d = 0; d < BTG_RADIX; ++d) rank[d * BTG_RADIX_GROUP + l] = 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint k = 0; k < BTG_RADIX_PER_ITEM; ++k)
        if (first + k < valid) rank[((tileKeys[first + k] >> shift) & BTG_RADIX_MASK) * BTG_RADIX_GROUP + l]++;
    barrier(CLK_LOCAL_MEM_FENCE);
    /* exclusive scan of rank in [d][l] order: work-item t takes entries [16 t, 16 t + 16) */
    uint s = 0u;
    for (uint k = 0; k < BTG_RADIX; ++k) s += rank[l * BTG_RADIX + k];
    uint run = radix_group_scan(sums, l, s);
    for (uint k = 0; k < BTG_RADIX; ++k) {
        const uint c = rank[l * BTG_RADIX + k];
        rank[l * BTG_RADIX + k] = (ushort)run;
        run += c;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
}

/* The tile's digit counts: counts[d * numTiles + tile]. Launch: numTiles groups of BTG_RADIX_GROUP. */
__kernel __attribute__((reqd_work_group_size(BTG_RADIX_GROUP, 1, 1)))
void radix_tile_count(__global const uint* restrict keys, __global uint* restrict counts, uint n, uint shift,
                      uint numTiles)
{
    __local uint perItem[BTG_RADIX * BTG_RADIX_GROUP]; /* [d][l]: work-item l's keys of digit d */
    const uint l = (uint)get_local_id(0), tile = (uint)get_group_id(0);
    uint own[BTG_RADIX];
    for (uint d = 0; d < BTG_RADIX; ++d) own[d] = 0u;
    for (uint j = 0; j < BTG_RADIX_PER_ITEM; ++j) {
        const uint i = tile * BTG_RADIX_TILE + j * BTG_RADIX_GROUP + l;
        if (i < n) own[(keys[i] >> shift) & BTG_RADIX_MASK]++;
    }
    for (uint d = 0; d < BTG_RADIX; ++d) perItem[d * BTG_RADIX_GROUP + l] = own[d];
    barrier(CLK_LOCAL_MEM_FENCE);
    /* digit d = l / 16 sums its row's 16 slices of 16; then the row's first adds them */
    const uint d = l / BTG_RADIX, part = l % BTG_RADIX;
    uint s = 0u;
    for (uint k = 0; k < BTG_RADIX_GROUP / BTG_RADIX; ++k) s += perItem[d * BTG_RADIX_GROUP + part * (BTG_RADIX_GROUP / BTG_RADIX) + k];
    barrier(CLK_LOCAL_MEM_FENCE);
    perItem[l] = s;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (part == 0u) {
        uint t = 0u;
        for (uint k = 0; k < BTG_RADIX; ++k) t += perItem[d * BTG_RADIX + k];
        counts[d * numTiles + tile] = t;
    }
}

/* counts[0, size) replaced by their exclusive prefix sums. Launch: one group of BTG_RADIX_GROUP. */
__kernel __attribute__((reqd_work_group_size(BTG_RADIX_GROUP, 1, 1)))
void radix_tile_offsets(__global uint* counts, uint size)
{
    __local uint sums[BTG_RADIX_GROUP];
    const uint l = (uint)get_local_id(0);
    const uint per = (size + BTG_RADIX_GROUP - 1u) / BTG_RADIX_GROUP;
    const uint begin = min(l * per, size), end = min(begin + per, size);
    uint s = 0u;
    for (uint i = begin; i < end; ++i) s += counts[i];
    uint run = radix_group_scan(sums, l, s);
    for (uint i = begin; i < end; ++i) {
        const uint c = counts[i];
        counts[i] = run;
        run += c;
    }
}

/* Each key of the tile to its digit d's offset for the tile plus its rank among the tile's keys
 * of digit d before it. scanned: offsets[d * numTiles + tile] is that offset (radix_tile_offsets
 * ran); else offsets holds the counts, and each work-group adds up the ones before its own (a
 * few tiles: one launch a pass the fewer). Launch: numTiles groups of BTG_RADIX_GROUP. */
__kernel __attribute__((reqd_work_group_size(BTG_RADIX_GROUP, 1, 1)))
void radix_tile_scatter(__global const uint* restrict keysIn, __global const uint* restrict valsIn,
                        __global uint* restrict keysOut, __global uint* restrict valsOut,
                        __global const uint* restrict offsets, uint n, uint shift, uint numTiles, uint scanned)
{
    __local uint tileKeys[BTG_RADIX_TILE];
    __local ushort rank[BTG_RADIX * BTG_RADIX_GROUP]; /* [d][l], then its exclusive scan in that order */
    __local uint sums[BTG_RADIX_GROUP];
    __local uint start[BTG_RADIX];                  /* where digit d's keys go, less the tile's keys of smaller digits */
    const uint l = (uint)get_local_id(0), tile = (uint)get_group_id(0);
    const uint tileBase = tile * BTG_RADIX_TILE;
    for (uint j = 0; j < BTG_RADIX_PER_ITEM; ++j) {
        const uint i = tileBase + j * BTG_RADIX_GROUP + l;
        tileKeys[j * BTG_RADIX_GROUP + l] = i < n ? keysIn[i] : 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    /* work-item l's keys: the tile's [l * PER_ITEM, (l + 1) * PER_ITEM), in order */
    const uint first = l * BTG_RADIX_PER_ITEM;
    radix_tile_ranks(rank, sums, tileKeys, tileBase < n ? n - tileBase : 0u, shift);
    /* Without the scan launch: digit d = l / 16's counts, every 16th tile from l % 16, those
     * before this tile and all of them, added up here (the barriers outside any branch: PoCL's
     * work-group loops want them so). */
    const uint row = l / BTG_RADIX;
    uint tilesBefore = 0u, all = 0u;
    for (uint t = l % BTG_RADIX; !scanned && t < numTiles; t += BTG_RADIX) {
        const uint c = offsets[row * numTiles + t];
        all += c;
        tilesBefore += t < tile ? c : 0u;
    }
    sums[l] = tilesBefore; /* the scan above is done with sums: free again */
    barrier(CLK_LOCAL_MEM_FENCE);
    uint rowBefore = 0u;
    if (l < BTG_RADIX)
        for (uint k = 0; k < BTG_RADIX; ++k) rowBefore += sums[l * BTG_RADIX + k];
    barrier(CLK_LOCAL_MEM_FENCE);
    sums[l] = all;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (l < BTG_RADIX) {
        uint below = 0u; /* the keys of every smaller digit, all tiles */
        for (uint k = 0; k < l * BTG_RADIX; ++k) below += sums[k];
        start[l] = (scanned ? offsets[l * numTiles + tile] : below + rowBefore) - rank[l * BTG_RADIX_GROUP];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint k = 0; k < BTG_RADIX_PER_ITEM; ++k) {
        const uint i = tileBase + first + k;
        if (i >= n) break;
        const uint key = tileKeys[first + k], d = (key >> shift) & BTG_RADIX_MASK;
        uint before = 0u;
        for (uint m = 0; m < k; ++m) before += ((tileKeys[first + m] >> shift) & BTG_RADIX_MASK) == d;
        const uint o = start[d] + rank[d * BTG_RADIX_GROUP + l] + before;
        keysOut[o] = key;
        valsOut[o] = valsIn[i];
    }
}

/* A sort of one tile (n <= BTG_RADIX_TILE) in one launch: every pass in local memory, the keys
 * and values ping-ponged between two local copies, each pass radix_tile_scatter's ranks
 * (radix_tile_ranks: for one tile each key's place less its rank among its own work-item's keys
 * of that digit). A small scene's sorts took two launches a pass, up to eight passes each; the
 * same stable order, so the same bits. Launch: one group of BTG_RADIX_GROUP. */
__kernel __attribute__((reqd_work_group_size(BTG_RADIX_GROUP, 1, 1)))
void radix_tile_sort(__global uint* keys, __global uint* vals, uint n, uint passes)
{
    __local uint keysA[BTG_RADIX_TILE], valsA[BTG_RADIX_TILE], keysB[BTG_RADIX_TILE], valsB[BTG_RADIX_TILE];
    __local ushort rank[BTG_RADIX * BTG_RADIX_GROUP];
    __local uint sums[BTG_RADIX_GROUP];
    const uint l = (uint)get_local_id(0), first = l * BTG_RADIX_PER_ITEM;
    for (uint j = 0; j < BTG_RADIX_PER_ITEM; ++j) {
        const uint i = j * BTG_RADIX_GROUP + l;
        keysA[i] = i < n ? keys[i] : 0u;
        valsA[i] = i < n ? vals[i] : 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    /* (the copies picked by pointers, the barriers outside any branch: PoCL's work-group loops
     * want them so) */
    __local uint* keysIn = keysA;
    __local uint* valsIn = valsA;
    __local uint* keysOut = keysB;
    __local uint* valsOut = valsB;
    for (uint pass = 0u; pass < passes; ++pass) {
        const uint shift = 4u * pass;
        radix_tile_ranks(rank, sums, keysIn, n, shift);
        for (uint k = 0; k < BTG_RADIX_PER_ITEM; ++k) {
            if (first + k >= n) break;
            const uint key = keysIn[first + k], d = (key >> shift) & BTG_RADIX_MASK;
            uint before = 0u;
            for (uint m = 0; m < k; ++m) before += ((keysIn[first + m] >> shift) & BTG_RADIX_MASK) == d;
            const uint o = rank[d * BTG_RADIX_GROUP + l] + before;
            keysOut[o] = key;
            valsOut[o] = valsIn[first + k];
        }
        barrier(CLK_LOCAL_MEM_FENCE);
        BTG_RADIX_SWAP(__local uint*, keysIn, keysOut);
        BTG_RADIX_SWAP(__local uint*, valsIn, valsOut);
    }
    for (uint j = 0; j < BTG_RADIX_PER_ITEM; ++j) {
        const uint i = j * BTG_RADIX_GROUP + l;
        if (i < n) {
            keys[i] = keysIn[i];
            vals[i] = valsIn[i];
        }
    }
}

/* A CPU device's whole sort in one work-item: 8-bit digits over `bits` bits (the passes' 4-bit
 * digits' bits, so the same keys are compared: the same stable order, the same bits), every
 * pass's counts from one read of the keys, and a pass whose keys all share one digit skipped (a
 * stable scatter into one bucket keeps the order). The passes took four launches each there
 * (counts, the scan's two, scatter; PoCL, cubes 8,000: the leaves' sort of 32,000 keys 2.3 ms a
 * step over eight passes). Ping-pongs through keysAlt / valsAlt and ends in keys / vals.
 * Launch: one work-item. */
__kernel void radix_serial_sort(__global uint* restrict keys, __global uint* restrict vals,
                                __global uint* restrict keysAlt, __global uint* restrict valsAlt, uint n, uint bits)
{
    if (get_global_id(0) != 0u) return;
    const uint passes = (bits + 7u) / 8u;
    /* the last pass's digit holds only the bits left (4 when bits is 4 mod 8) */
    uint masks[4];
    uint counts[4][256];
    for (uint p = 0u; p < passes; ++p) {
        masks[p] = bits - 8u * p >= 8u ? 255u : (1u << (bits - 8u * p)) - 1u;
        for (uint d = 0u; d < 256u; ++d) counts[p][d] = 0u;
    }
    for (uint i = 0u; i < n; ++i) {
        const uint k = keys[i];
        for (uint p = 0u; p < passes; ++p) counts[p][(k >> (8u * p)) & masks[p]]++;
    }
    __global uint* kIn = keys;
    __global uint* vIn = vals;
    __global uint* kOut = keysAlt;
    __global uint* vOut = valsAlt;
    for (uint p = 0u; p < passes; ++p) {
        const uint shift = 8u * p, mask = masks[p];
        uint sum = 0u, single = 0u;
        for (uint d = 0u; d <= mask; ++d) {
            const uint c = counts[p][d];
            single |= c == n;
            counts[p][d] = sum;
            sum += c;
        }
        if (single) continue;
        for (uint i = 0u; i < n; ++i) {
            const uint k = kIn[i];
            const uint o = counts[p][(k >> shift) & mask]++;
            kOut[o] = k;
            vOut[o] = vIn[i];
        }
        BTG_RADIX_SWAP(__global uint*, kIn, kOut);
        BTG_RADIX_SWAP(__global uint*, vIn, vOut);
    }
    if (kIn != keys)
        for (uint i = 0u; i < n; ++i) {
            keys[i] = kIn[i];
            vals[i] = vIn[i];
        }
}
