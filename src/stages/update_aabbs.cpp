// update_aabbs.cpp — host launcher of kernels/update_aabbs.cl: one work-item per body row.
#include "stages/update_aabbs.h"

#include "cl/program.h"

namespace btgpu {

void updateAabbs(DeviceWorld& w, float threshold)
{
    if (w.numBodies <= 0) return;
    w.aabbMin.reserve(w.ctx, size_t(w.numBodies));
    w.aabbMax.reserve(w.ctx, size_t(w.numBodies));
    cl::Launch(w.ctx, w.ctx.program("update_aabbs").kernel("update_aabbs"), &w.profiler)
        .arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes).arg(w.aabbMin).arg(w.aabbMax)
        .arg(cl_int(w.numBodies)).arg(threshold)
        .run(size_t(w.numBodies));
}

}  // namespace btgpu
