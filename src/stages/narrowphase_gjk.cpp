// narrowphase_gjk.cpp — host launchers of the narrowphase programs whose pairs keep persistent
// manifolds (the GJK kinds; two boxes, program "narrowphase_sat"): one kernel per row of the
// pair-kind table the plan has, each striding over its kind's range; and the store of the
// persistent manifolds beside the warm-start cache. The GJK cache is kept as large as the
// warm-start cache, whose indices it shares.
#include "stages/narrowphase_gjk.h"

#include "cl/program.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace btgpu {

namespace {
constexpr const char* kPersistentPrograms[] = {"narrowphase_sat", "narrowphase_gjk", "narrowphase_mesh"};

void reserveGjk(DeviceWorld& w)
{
    w.gjkPairState.reserveExact(w.ctx, std::max<size_t>(w.pairCapacity, 1));
    w.gjkCache.reserveExact(w.ctx, std::max<size_t>(w.contactCache.capacity(), 1), true);
}
}  // namespace

void preparePersistent(DeviceWorld& w, const PairKinds& kinds)
{
    w.contactCache.reserveExact(w.ctx, std::max<size_t>(w.contactCache.capacity(), 1), true);
    if (!keepsPersistentManifolds(kinds, w.speculativeContacts)) {
        // No pair keeps a manifold: one entry of no kind each, for the kernels that bind them
        // (the readers find no persistent state at slot 0; the collide kernels write none).
        if (w.gjkPairState.capacity() != 1 || w.gjkCache.capacity() != 1) {
            const std::vector<BtgPersistentManifold> none(1, BtgPersistentManifold{});
            w.gjkPairState.release();
            w.gjkPairState.reserveExact(w.ctx, 1);
            w.gjkPairState.upload(w.ctx, none);
            w.gjkCache.release();
            w.gjkCache.reserveExact(w.ctx, 1);
            w.gjkCache.upload(w.ctx, none);
        }
        w.gjkCacheCurrent = false;
        return;
    }
    reserveGjk(w);
    if (!w.gjkCacheCurrent) {
        // Entries no store of this kind wrote (a fresh buffer, or one left from before the plan
        // last had these kinds) must match no pair: kind 0 is BTG_PAIR_NONE.
        std::vector<BtgPersistentManifold> none(w.gjkCache.capacity(), BtgPersistentManifold{});
        w.gjkCache.upload(w.ctx, none);
        w.gjkCacheCurrent = true;
    }
}

int persistentStateCapacity(const DeviceWorld& w, const PairKinds& kinds)
{
    return keepsPersistentManifolds(kinds, w.speculativeContacts) ? int(w.gjkPairState.capacity()) : 0;
}

void narrowphasePersistent(DeviceWorld& w, const PairKinds& kinds, const char* kProgram)
{
    if (!kinds.anyIn(kProgram) || w.pairCapacity == 0) return;
    w.manifolds.reserveExact(w.ctx, w.pairCapacity);
    w.pairManifolds.reserveExact(w.ctx, w.pairCapacity);
    preparePersistent(w, kinds);
    const size_t items = std::min(w.pairCapacity, size_t(std::max<cl_uint>(w.ctx.device().computeUnits, 1)) * 1024);
    const cl_int indirect = w.pairKindsIndirect ? 1 : 0;
    const int cacheCapacity = int(w.contactCache.capacity());
    const int gjkCapacity = int(w.gjkCache.capacity());
    // The soft step collides box pairs, sphere pairs and hulls on planes afresh (each program's
    // BTG_SPECULATIVE_PAIR); the other pairs keep their manifolds in both modes.
    const cl_int speculative = w.speculativeContacts ? 1 : 0;
    // One kernel strides over all the program's kinds (collide_persistent).
    cl::Launch(w.ctx, w.ctx.program(kProgram).kernel("collide_persistent"), &w.profiler)
        .arg(w.pairs).arg(w.pairOrder).arg(w.pairKindRanges).arg(indirect).arg(w.pos).arg(w.rot).arg(w.props)
        .arg(w.shapes).arg(w.children).arg(w.hullVertices).arg(w.hullFaces).arg(w.hullIndices).arg(w.hullEdges)
        .arg(w.counters).arg(w.contactCache).arg(cacheCapacity)
        .arg(w.gjkCache).arg(gjkCapacity).arg(w.manifolds).arg(w.pairManifolds).arg(w.gjkPairState).arg(speculative)
        .arg(persistentStateCapacity(w, kinds)).run(items);
    // The soft step's fresh pairs of the GJK program (btgSoftCollidesAfresh: two spheres, a box
    // or hull on a plane) have a kernel of their own, which collide_persistent leaves them to.
    const bool fresh = kinds.has(BTG_PAIR_SPHERE_SPHERE) || kinds.has(BTG_PAIR_HULL_PLANE) ||
                       kinds.has(BTG_PAIR_PLANE_BOX) || kinds.has(BTG_PAIR_PLANE_CONVEX);
    if (speculative && fresh && std::strcmp(kProgram, "narrowphase_gjk") == 0)
        cl::Launch(w.ctx, w.ctx.program(kProgram).kernel("collide_fresh"), &w.profiler)
            .arg(w.pairs).arg(w.pairOrder).arg(w.pairKindRanges).arg(indirect).arg(w.pos).arg(w.rot).arg(w.props)
            .arg(w.shapes).arg(w.children).arg(w.hullVertices).arg(w.hullFaces).arg(w.hullIndices).arg(w.hullEdges)
            .arg(w.manifolds).arg(w.pairManifolds).arg(w.gjkPairState).arg(persistentStateCapacity(w, kinds))
            .run(items);
}

void storePersistentManifolds(DeviceWorld& w, const PairKinds& kinds, unsigned solverFlags)
{
    // Each program holds the same store kernel: the first the plan builds anyway.
    const char* kProgram = kPersistentPrograms[0];
    for (const char* program : kPersistentPrograms)
        if (kinds.anyIn(program)) {
            kProgram = program;
            break;
        }
    reserveGjk(w);
    w.gjkCacheNext.reserveExact(w.ctx, w.gjkCache.capacity());
    w.cachePos.reserve(w.ctx, std::max<size_t>(w.contactCapacity, 1));
    w.carryRank.reserve(w.ctx, 1);
    w.carryPos.reserve(w.ctx, 1);
    w.subPairs.reserve(w.ctx, 1);  // read only for a manifold past the pair slots: a convex–concave group
    const int contactCapacity = int(std::min({w.contactCapacity, w.contacts.capacity(), w.contactManifolds.capacity()}));
    const int gjkCapacity = int(w.gjkCache.capacity());
    cl::Program& prog = w.ctx.program(kProgram);
    cl::Launch(w.ctx, prog.kernel("store_persistent_manifolds"), &w.profiler)
        .arg(w.contactManifolds).arg(w.manifolds).arg(w.counters).arg(contactCapacity).arg(w.props).arg(w.shapes)
        .arg(w.pairs).arg(w.children).arg(w.gjkPairState).arg(int(w.gjkPairState.capacity())).arg(w.gjkCache).arg(gjkCapacity)
        .arg(w.contacts).arg(cl_uint(solverFlags)).arg(cl_uint(w.pairCapacity)).arg(w.subPairs)
        .arg(cl_uint(w.subPairCapacity)).arg(w.gjkCacheNext).arg(w.cachePos)
        .run(size_t(std::max({contactCapacity, gjkCapacity, 1})));
    // the entries storeContactCache carried through a sleep (w.carrying: it did, ranked over this capacity)
    const size_t cacheCapacity = w.contactCache.capacity();
    if (w.carrying)
        cl::Launch(w.ctx, prog.kernel("carry_persistent_manifolds"), &w.profiler)
            .arg(w.gjkCache).arg(gjkCapacity).arg(w.counters).arg(int(cacheCapacity)).arg(contactCapacity)
            .arg(w.carryRank).arg(w.carryPos).arg(w.gjkCacheNext)
            .run(cacheCapacity);
    std::swap(w.gjkCache, w.gjkCacheNext);
}

void forgetConcaveManifolds(DeviceWorld& w, const std::vector<int>& rows)
{
    // Rare (an app's terrain edit): the whole cache down and up, no kernel of its own.
    if (rows.empty() || w.gjkCache.capacity() == 0 || !w.gjkCacheCurrent) return;
    std::vector<BtgPersistentManifold> cache = w.gjkCache.download(w.ctx, w.gjkCache.capacity());
    bool any = false;
    for (BtgPersistentManifold& m : cache)
        if (btgIsConcaveKind(m.kind) && (std::find(rows.begin(), rows.end(), m.bodyA) != rows.end() ||
                                         std::find(rows.begin(), rows.end(), m.bodyB) != rows.end())) {
            m.kind = BTG_PAIR_NONE;
            any = true;
        }
    if (any) w.gjkCache.upload(w.ctx, cache);
}

}  // namespace btgpu
