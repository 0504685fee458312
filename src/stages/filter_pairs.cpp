// filter_pairs.cpp — host launcher of the pair filter: one work-item per ignored pair.
#include "stages/filter_pairs.h"

#include "cl/program.h"

#include <algorithm>

namespace btgpu {

void filterPairs(DeviceWorld& w)
{
    if (w.numIgnoredPairs <= 0) return;
    const int capacity = int(std::min(w.pairCapacity, w.pairs.capacity()));
    cl::Launch(w.ctx, w.ctx.program("filter_pairs").kernel("filter_ignored_pairs"), &w.profiler)
        .arg(w.ignoredPairs).arg(w.numIgnoredPairs).arg(w.pairs).arg(w.counters).arg(capacity).arg(w.pairManifolds)
        .run(size_t(w.numIgnoredPairs));
}

}  // namespace btgpu
