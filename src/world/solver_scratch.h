// solver_scratch.h — device scratch owned by the contact stages (contact compaction block sums,
// per-body coloring claims, the Jacobi solver's per-body contact lists and velocity changes). One member of DeviceWorld, so those stages add no columns of their
// own to the shared world layout.
#pragma once
#include "shared/soft_rows.h"
#include "shared/types.h"
#include "stages/prims/scan.h"

#include <algorithm>

namespace btgpu {

struct SolverScratch {
    cl::DeviceArray<uint> blockSums;  // contact_cache: per-work-group counts, then offsets
    cl::DeviceArray<uint> bodyClaim;  // color_constraints: lowest contact priority claiming a body (two halves and a word a sub-round in color_resident)
    cl::DeviceArray<int> bodyColor;   // color_constraints: the color that last took the body
    cl::DeviceArray<int> colorActive; // color_serial: the edges still uncoloured and those still eligible in a colour
    // solve_constraints: contacts of color c are colorOrder[colorStart[c], colorStart[c + 1]);
    // a second list (counts and starts after numColors + 1, indices after one per contact
    // slot) holds only the contacts with a split-impulse target, for the push passes
    cl::DeviceArray<uint> colorCount;  // 2 x (numColors + 1): per color, then the fill cursor
    cl::DeviceArray<uint> colorStart;  // 2 x (numColors + 1)
    cl::DeviceArray<int> colorOrder;   // two per contact slot
    // solve_constraints' per-colour launches: list 0's contacts copied in colour order (slot k:
    // contact colorOrder[k]), which the velocity sweeps solve (contacts_gather / contacts_scatter)
    cl::DeviceArray<BtgContact> sortedContacts;
    // ... and with the wide sweeps (pgs_wide_passes.h) each body's solver record (4 rows) and kind
    cl::DeviceArray<BtgFloat4> wideBodies;
    cl::DeviceArray<int> wideKinds;
    cl::DeviceArray<uint> gridBarrier; // solve_resident's arrival count, generation, timeout flag
    cl::DeviceArray<uint> softBarrier; // soft_resident's (btgGridBarrierCounting: zeroed before each launch)
    // solve_soft (SolverKind::SoftStep): each contact slot's soft rows, and BTG_SOFT_BODY_ROWS per
    // body (position and rotation deltas, the forces' velocity change per substep); the color
    // ranges above hold one list there, over every edge (the last range the leftovers);
    // a contact's soft rows sit at its place in that list (edgeSlot), read in color order
    cl::DeviceArray<BtgSoftContact> softContacts;
    // After the solve the soft rows are dead until the next substep's: their storage then holds
    // the new warm-start cache (storeContactCache, copied back over the old) and, in a call's
    // last substep, the contact reports until syncOut has read them (reportContacts). So the
    // soft step keeps one cache buffer and no report buffer of its own: 144 + 368 bytes a
    // contact slot less. n elements of T, the storage grown to hold them where it must.
    template <typename T>
    cl::ArrayView<T> rowsAs(cl::Context& ctx, size_t n)
    {
        n = std::max<size_t>(n, 1);
        softContacts.reserveExact(ctx, (n * sizeof(T) + sizeof(BtgSoftContact) - 1) / sizeof(BtgSoftContact));
        return cl::ArrayView<T>::over(softContacts, n);
    }
    // n elements of a column that lives only after the solve: over the soft rows (the soft step
    // solved: `own` released) or in its own buffer (the other solvers).
    template <typename T>
    cl::ArrayView<T> afterSolve(cl::Context& ctx, cl::DeviceArray<T>& own, size_t n, bool overSoftRows)
    {
        if (overSoftRows) {
            own.release();
            return rowsAs<T>(ctx, n);
        }
        own.reserveExact(ctx, std::max<size_t>(n, 1));
        return cl::ArrayView<T>(own);
    }
    cl::DeviceArray<int> edgeSlot;
    // each body's edges (dynamic sides only, sorted), the warm start's gather:
    // softListEntries[softListStart[b], softListStart[b + 1])
    cl::DeviceArray<uint> softListStart;   // N + 1
    cl::DeviceArray<uint> softListCursor;  // N: counts, then fill cursors
    cl::DeviceArray<uint> softListEntries; // 2 per edge slot
    ScanScratch softListScan;
    cl::DeviceArray<BtgFloat4> softBodies;
    cl::DeviceArray<BtgFloat4> softSolver;  // 4 per body: its solver record for the step (solve_soft.cl)
    // a CPU device's wide sweeps (soft_wide.h): per regular colour its first chunk of eight slots,
    // per chunk its block of contact lanes (BTG_WC_FIELDS x 8 floats) and its lanes' modes and bodies
    cl::DeviceArray<uint> softWideStart;  // numColors
    cl::DeviceArray<float> softWideBlock;
    cl::DeviceArray<int> softWideLanes;   // 3 x 8 per chunk
    // Room for the wide sweeps' chunks (the soft step's or the bullet mode's: they never share a
    // step) over `slots` edge slots in numColors colours, at most one part-empty chunk a colour
    // beyond the slots' eighths, `fields` floats a lane.
    void reserveWide(cl::Context& ctx, size_t slots, int numColors, size_t fields)
    {
        const size_t chunks = slots / BTG_SOFT_WIDE + size_t(numColors);
        softWideStart.reserve(ctx, size_t(numColors));
        softWideBlock.reserve(ctx, chunks * fields * BTG_SOFT_WIDE);
        softWideLanes.reserve(ctx, chunks * 3 * BTG_SOFT_WIDE);
    }
    // the resident soft step's flow (solve_soft.cl): 2 per edge slot (each side's place among its
    // body's edges, and their number), 1 per body (its edges done so far this step)
    cl::DeviceArray<uint> softFlowRank;
    cl::DeviceArray<uint> softFlowDone;
    cl::DeviceArray<uint> softFlowDeg;  // 1 per body: its edges a sweep (the flow's body passes)
    // the resident solve's flow (solve_constraints.cl): 4 per body (a bit per colour and list
    // where it is a dynamic side), 2 per body (its velocity and push sweeps' edges done)
    cl::DeviceArray<uint> pgsFlowMasks;
    cl::DeviceArray<uint> pgsFlowDone;
    // solve_jacobi: body b's contacts are jacobiEntries[jacobiStart[b], jacobiStart[b + 1]),
    // each 2 * contact + side, in increasing order; jacobiDeltas holds 4 per contact slot
    // (A lin, A ang, B lin, B ang: m/s, rad/s), the change each contact made to its copies.
    cl::DeviceArray<uint> jacobiStart;    // N + 1
    cl::DeviceArray<uint> jacobiCursor;   // N: counts, then fill cursors
    cl::DeviceArray<uint> jacobiEntries;  // 2 per contact slot
    cl::DeviceArray<BtgFloat4> jacobiDeltas;
    ScanScratch jacobiScan;
};

}  // namespace btgpu
