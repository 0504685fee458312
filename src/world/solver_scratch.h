// solver_scratch.h — device scratch owned by the contact stages (contact compaction block sums,
// per-body coloring claims). One member of DeviceWorld, so those stages add no columns of their
// own to the shared world layout.
#pragma once
#include "cl/buffer.h"

namespace btgpu {

struct SolverScratch {
    cl::DeviceArray<uint> blockSums;  // contact_cache: per-work-group counts, then offsets
    cl::DeviceArray<int> bodyClaim;   // color_constraints: lowest contact priority claiming a body
    cl::DeviceArray<int> bodyColor;   // color_constraints: the color that last took the body
};

}  // namespace btgpu
