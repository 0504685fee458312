// narrowphase.cpp — launches one contact kernel per pair kind the plan names; each kernel
// early-outs on pairs of other kinds, so together they write every pair's manifold once.
// The SAT program is built only when hull–hull pairs exist.
#include "stages/narrowphase.h"

#include "cl/program.h"

namespace btgpu {

void narrowphaseSimple(DeviceWorld& w, const PairKinds& kinds)
{
    if (!kinds.simple() || w.pairCapacity == 0) return;
    w.manifolds.reserveExact(w.ctx, w.pairCapacity);
    const cl_uint capacity = static_cast<cl_uint>(w.pairCapacity);
    const size_t n = w.pairCapacity;
    {
        cl::Program& prog = w.ctx.program("narrowphase");
        if (kinds.sphereSphere)
            cl::Launch(w.ctx, prog.kernel("collide_sphere_sphere"), &w.profiler)
                .arg(w.pairs).arg(w.counters).arg(capacity).arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes)
                .arg(w.manifolds).run(n);
        if (kinds.spherePlane)
            cl::Launch(w.ctx, prog.kernel("collide_sphere_plane"), &w.profiler)
                .arg(w.pairs).arg(w.counters).arg(capacity).arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes)
                .arg(w.manifolds).run(n);
        if (kinds.sphereHull)
            cl::Launch(w.ctx, prog.kernel("collide_sphere_hull"), &w.profiler)
                .arg(w.pairs).arg(w.counters).arg(capacity).arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes)
                .arg(w.hullVertices).arg(w.hullFaces).arg(w.hullIndices).arg(w.manifolds).run(n);
        if (kinds.hullPlane)
            cl::Launch(w.ctx, prog.kernel("collide_hull_plane"), &w.profiler)
                .arg(w.pairs).arg(w.counters).arg(capacity).arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes)
                .arg(w.hullVertices).arg(w.manifolds).run(n);
    }
}

void narrowphaseSat(DeviceWorld& w)
{
    if (w.pairCapacity == 0) return;
    w.manifolds.reserveExact(w.ctx, w.pairCapacity);
    const cl_uint capacity = static_cast<cl_uint>(w.pairCapacity);
    const size_t n = w.pairCapacity;
    cl::Launch(w.ctx, w.ctx.program("narrowphase_sat").kernel("collide_hull_hull"), &w.profiler)
            .arg(w.pairs).arg(w.counters).arg(capacity).arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes)
            .arg(w.hullVertices).arg(w.hullFaces).arg(w.hullIndices).arg(w.hullEdges)
            .arg(w.manifolds).run(n);
}

void narrowphase(DeviceWorld& w, const PairKinds& kinds)
{
    narrowphaseSimple(w, kinds);
    if (kinds.hullHull) narrowphaseSat(w);
}

}  // namespace btgpu
