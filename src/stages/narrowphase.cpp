// narrowphase.cpp — launches the kernel of each pair-kind row (world/pair_kinds.h) whose kind
// the plan has, all with the same arguments; each strides over its kind's range of the
// kind-grouped pairs (find_pairs), so together they write every pair's manifold once. A
// program is built only when one of its kinds is present (the SAT program only for box–box
// pairs).
#include "stages/narrowphase.h"

#include "cl/program.h"
#include "stages/narrowphase_gjk.h"

#include <algorithm>
#include <cstring>

namespace btgpu {

void narrowphaseProgram(DeviceWorld& w, const PairKinds& kinds, const char* program)
{
    // Programs whose pairs keep a persistent manifold take its arguments too.
    if (std::strcmp(program, "narrowphase_gjk") == 0 || std::strcmp(program, "narrowphase_sat") == 0)
        return narrowphasePersistent(w, kinds, program);
    if (!kinds.anyIn(program) || w.pairCapacity == 0) return;
    if (std::strcmp(program, "narrowphase_mesh") == 0) return narrowphaseMesh(w, kinds);
    w.manifolds.reserveExact(w.ctx, w.pairCapacity);
    w.pairManifolds.reserveExact(w.ctx, w.pairCapacity);
    // A range's size is known on the device only: a fixed number of work-items strides over it,
    // enough to fill the device, never more than there are pair slots.
    const size_t items = std::min(w.pairCapacity, size_t(std::max<cl_uint>(w.ctx.device().computeUnits, 1)) * 1024);
    const cl_int indirect = w.pairKindsIndirect ? 1 : 0;
    cl::Program& prog = w.ctx.program(program);
    for (int r = 0; r < kNumPairKindRows; ++r) {
        const PairKindRow& row = kPairKindRows[r];
        if (!kinds.has(row.kind) || std::strcmp(row.program, program) != 0) continue;
        cl::Launch(w.ctx, prog.kernel(row.kernel), &w.profiler)
            .arg(w.pairs).arg(w.pairOrder).arg(w.pairKindRanges).arg(indirect).arg(w.pos).arg(w.rot).arg(w.props)
            .arg(w.shapes).arg(w.children).arg(w.hullVertices).arg(w.hullFaces).arg(w.hullIndices).arg(w.hullEdges)
            .arg(w.manifolds).arg(w.pairManifolds).run(items);
    }
}

void narrowphaseMesh(DeviceWorld& w, const PairKinds& kinds)
{
    const char* program = "narrowphase_mesh";
    if (!kinds.anyIn(program) || w.pairCapacity == 0) return;
    cl::Context& ctx = w.ctx;
    w.pairManifolds.reserveExact(ctx, w.pairCapacity);
    preparePersistent(w, kinds);
    // The bullet mode steps each pair's persistent manifold as stock's; the soft step clips afresh.
    const cl_int persistent = w.speculativeContacts ? 0 : 1;
    const size_t units = size_t(std::max<cl_uint>(ctx.device().computeUnits, 1)) * 1024;
    const cl_uint capacity = cl_uint(w.subPairCapacity), base = cl_uint(w.pairCapacity);
    const cl_uint countSlots = cl_uint(w.pairCapacity + 1);
    cl::Program& prog = ctx.program(program);
    auto triangles = [&](const char* kernel) {
        cl::Launch(ctx, prog.kernel(kernel), &w.profiler)
            .arg(w.subPairs).arg(w.counters).arg(capacity).arg(w.pairs).arg(w.pos).arg(w.rot).arg(w.props)
            .arg(w.shapes).arg(w.children).arg(w.hullVertices).arg(w.hullFaces).arg(w.hullIndices).arg(w.hullEdges)
            .arg(w.meshes).arg(w.meshNodes).arg(w.meshParts).arg(w.meshTriangles).arg(w.meshVertices)
            .arg(w.heightfields).arg(w.heightfieldHeights).arg(w.manifolds).arg(base)
            .run(std::min(w.subPairCapacity, units));
    };
    // The bullet mode's one point a triangle is one routine for every kind: one launch.
    if (persistent) triangles("collide_triangle_points");
    for (int r = 0; r < kNumPairKindRows && !persistent; ++r) {
        const PairKindRow& row = kPairKindRows[r];
        if (kinds.has(row.kind) && std::strcmp(row.program, program) == 0) triangles(row.kernel);
    }
    cl::Launch(ctx, prog.kernel("gather_mesh_manifolds"), &w.profiler)
        .arg(w.pairKindRanges).arg(w.pairOrder).arg(cl_int(w.pairKindsIndirect ? 1 : 0)).arg(w.pairs)
        .arg(w.subPairOffsets).arg(countSlots).arg(capacity).arg(w.manifolds).arg(base).arg(w.pairManifolds)
        .arg(persistent).arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes).arg(w.children).arg(w.counters)
        .arg(w.contactCache).arg(int(w.contactCache.capacity())).arg(w.gjkCache).arg(int(w.gjkCache.capacity()))
        .arg(w.gjkPairState).arg(persistentStateCapacity(w, kinds))
        .run(std::min(w.pairCapacity, units));
}

void narrowphase(DeviceWorld& w, const PairKinds& kinds)
{
    for (int p = 0; p < kNumNarrowphasePrograms; ++p) {
        if (std::strcmp(kNarrowphasePrograms[p].program, "narrowphase_mesh") == 0) narrowphaseMesh(w, kinds);
        else narrowphaseProgram(w, kinds, kNarrowphasePrograms[p].program);
    }
}

}  // namespace btgpu
