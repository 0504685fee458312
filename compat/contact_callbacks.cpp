// contact_callbacks.cpp — gContactAddedCallback between a GPU-path step's contacts and its
// solve (see contact_callbacks.h), read against Bullet 3.24's btManifoldResult::addContactPoint:
// the point the callback gets is the one addContactPoint adds or replaces (Bullet's body order,
// world and local points, combined coefficients from the combiner callbacks with the pair's
// objects in the pair cache's order, btPlaneSpace1's lateral directions, part ids and indices),
// and the wrappers are stock's (a compound's child with its world transform, a mesh's or
// heightfield's triangle as a btTriangleShape in the concave body's frame).
#include "contact_callbacks.h"

#include "manifold_sync.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

namespace btgpu {

namespace {

int proxyId(const btCollisionObject* o) { return o->getBroadphaseHandle() ? o->getBroadphaseHandle()->m_uniqueId : 0; }

// One side of a device manifold as stock's wrapper shows it.
struct SideShape {
    const btCollisionObject* object;
    const btCollisionShape* shape;  // the leaf (a compound's child) or the whole shape
    btTransform transform;          // the leaf's world transform
    bool concave;                   // per point a triangle of `shape`
};

SideShape sideShape(const btCollisionObject* o, int index)
{
    SideShape s{o, o->getCollisionShape(), o->getWorldTransform(), false};
    if (s.shape->isCompound()) {
        const auto* c = static_cast<const btCompoundShape*>(s.shape);
        if (index >= 0 && index < c->getNumChildShapes()) {
            s.shape = c->getChildShape(index);
            s.transform = o->getWorldTransform() * c->getChildTransform(index);
        }
    }
    s.concave = s.shape->isConcave();
    return s;
}

// The triangle (partId, index) of a concave shape near a point in its frame, as the shape's own
// processAllTriangles hands it to stock's convex–concave algorithm.
struct TriangleFinder : btTriangleCallback {
    int part, index;
    bool found = false;
    btVector3 v[3];
    TriangleFinder(int p, int i) : part(p), index(i) {}
    void processTriangle(btVector3* t, int partId, int triangleIndex) override
    {
        if (found || partId != part || triangleIndex != index) return;
        v[0] = t[0];
        v[1] = t[1];
        v[2] = t[2];
        found = true;
    }
};

bool findTriangle(const btCollisionShape* concave, const btVector3& local, int part, int index, btVector3 v[3])
{
    TriangleFinder finder(part, index);
    const btVector3 reach(btScalar(0.1), btScalar(0.1), btScalar(0.1));
    static_cast<const btConcaveShape*>(concave)->processAllTriangles(&finder, local - reach, local + reach);
    if (!finder.found) return false;
    v[0] = finder.v[0];
    v[1] = finder.v[1];
    v[2] = finder.v[2];
    return true;
}

bool sameVec(const btVector3& a, const btVector3& b) { return a.x() == b.x() && a.y() == b.y() && a.z() == b.z(); }

// What the callback may change that the device's contact does not carry (the solver reads
// these, 3.24's convertContact and setupContactConstraint): "" when it left them all.
const char* uncarriedChange(const btManifoldPoint& a, const btManifoldPoint& b)
{
    if (a.m_contactPointFlags != b.m_contactPointFlags) return "m_contactPointFlags";
    if (a.m_combinedRollingFriction != b.m_combinedRollingFriction) return "m_combinedRollingFriction";
    if (a.m_combinedSpinningFriction != b.m_combinedSpinningFriction) return "m_combinedSpinningFriction";
    if (a.m_contactMotion1 != b.m_contactMotion1 || a.m_contactMotion2 != b.m_contactMotion2) return "m_contactMotion";
    if (a.m_contactCFM != b.m_contactCFM || a.m_contactERP != b.m_contactERP) return "m_contactCFM/ERP";
    if (a.m_frictionCFM != b.m_frictionCFM) return "m_frictionCFM";
    if (a.m_appliedImpulse != b.m_appliedImpulse || a.m_appliedImpulseLateral1 != b.m_appliedImpulseLateral1 ||
        a.m_appliedImpulseLateral2 != b.m_appliedImpulseLateral2)
        return "the applied impulses (warm start)";
    return "";
}

}  // namespace

bool ContactCallbacks::customCombiners()
{
    return gCalculateCombinedFrictionCallback != &btManifoldResult::calculateCombinedFriction ||
           gCalculateCombinedRestitutionCallback != &btManifoldResult::calculateCombinedRestitution ||
           gCalculateCombinedRollingFrictionCallback != &btManifoldResult::calculateCombinedRollingFriction ||
           gCalculateCombinedSpinningFrictionCallback != &btManifoldResult::calculateCombinedSpinningFriction;
}

bool ContactCallbacks::customMaterials(const btDiscreteDynamicsWorld& world)
{
    if (!gContactAddedCallback) return false;
    const btCollisionObjectArray& objs = world.getCollisionObjectArray();
    for (int i = 0; i < objs.size(); ++i)
        if (objs[i]->getCollisionFlags() & btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK) return true;
    return false;
}

bool ContactCallbacks::wanted(const btDiscreteDynamicsWorld& world)
{
    return customCombiners() || gContactProcessedCallback || customMaterials(world);
}

ContactCallbacks::Set ContactCallbacks::current()
{
    return {gContactAddedCallback,
            gContactProcessedCallback,
            gCalculateCombinedFrictionCallback,
            gCalculateCombinedRestitutionCallback,
            gCalculateCombinedRollingFrictionCallback,
            gCalculateCombinedSpinningFrictionCallback};
}

bool ContactCallbacks::events()
{
    return gContactStartedCallback || gContactEndedCallback || gContactProcessedCallback || gContactDestroyedCallback;
}

std::string ContactCallbacks::unservedReason(const btDiscreteDynamicsWorld& world, const Config& config)
{
    if (config.internalSubsteps > 1 && overlapFilter(const_cast<btDiscreteDynamicsWorld&>(world)))
        return "overlap filter callback (setOverlapFilterCallback) with Config::internalSubsteps > 1 (Bullet's "
               "broadphase asks it once per internal step)";
    if (events() && config.internalSubsteps > 1)
        return "contact callbacks (gContactStarted/Ended/Processed/DestroyedCallback) with Config::internalSubsteps > 1 "
               "(stock calls them once per internal step)";
    if (events() && !config.fillDispatcherManifolds)
        return "contact callbacks (gContactStarted/Ended/Processed/DestroyedCallback) with "
               "Config::fillDispatcherManifolds off (they are the dispatcher manifolds' events)";
    if (config.internalSubsteps > 1 && (customMaterials(world) || customCombiners()))
        return customMaterials(world) ? "gContactAddedCallback with CF_CUSTOM_MATERIAL_CALLBACK and Config::internalSubsteps "
                                        "> 1 (stock calls it once per internal step)"
                                      : "a custom friction or restitution combiner (gCalculateCombined*Callback) with "
                                        "Config::internalSubsteps > 1 (stock calls it once per internal step)";
    return "";
}

bool ContactCallbacks::overlapFilter(btDiscreteDynamicsWorld& world)
{
    btOverlappingPairCache* cache = world.getBroadphase() ? world.getBroadphase()->getOverlappingPairCache() : nullptr;
    return cache && cache->getOverlapFilterCallback();
}

void ContactCallbacks::keepStockPairs(DeviceWorld& w, const RowMap& rows, btDiscreteDynamicsWorld& world)
{
    btOverlappingPairCache* cache = world.getBroadphase()->getOverlappingPairCache();
    const std::vector<BtgPair> pairs = downloadPairs(w);
    std::vector<uint> refused;
    for (size_t i = 0; i < pairs.size(); ++i) {
        btCollisionObject* a = pairs[i].a >= 0 && size_t(pairs[i].a) < rows.size() ? rows.at(size_t(pairs[i].a)) : nullptr;
        btCollisionObject* b = pairs[i].b >= 0 && size_t(pairs[i].b) < rows.size() ? rows.at(size_t(pairs[i].b)) : nullptr;
        btBroadphaseProxy* pa = a ? a->getBroadphaseHandle() : nullptr;
        btBroadphaseProxy* pb = b ? b->getBroadphaseHandle() : nullptr;
        if (!pa || !pb || !cache->findPair(pa, pb)) refused.push_back(uint(i));
    }
    clearPairRanges(w, refused);
}

bool ContactCallbacks::run(DeviceWorld& w, const RowMap& rows, const std::unordered_set<const btCollisionObject*>& removed,
                           ManifoldSync& sync)
{
    m_reason.clear();
    m_calls = 0;
    m_changed.clear();
    m_materials.clear();
    w.numMaterials = 0;
    // A custom combiner is evaluated for every point (stock: btManifoldResult::addContactPoint),
    // the processed callback called for every point (btPersistentManifold::refreshContactPoints);
    // the added callback only for pairs with a flagged body.
    const bool all = customCombiners() || gContactProcessedCallback;
    const std::vector<GatheredManifold> gathered = gatherCallbackManifolds(w, all);
    for (const GatheredManifold& g : gathered) {
        const BtgManifold& m = g.manifold;
        const ManifoldSync::Side side = ManifoldSync::orient(rows, m.bodyA, m.bodyB, m.indexA, m.indexB, removed);
        if (!side.valid) continue;
        // Stock's dispatcher collides no pair of two inactive bodies (needsCollision): no points
        // are added or refreshed there (the device keeps their contacts for the solve).
        if (!rows.at(size_t(m.bodyA))->isActive() && !rows.at(size_t(m.bodyB))->isActive()) continue;
        const bool swap = side.swap;
        SideShape sA = sideShape(rows.at(size_t(m.bodyA)), m.indexA);
        SideShape sB = sideShape(rows.at(size_t(m.bodyB)), m.indexB);
        const btCollisionObject* o0 = swap ? sB.object : sA.object;
        const btCollisionObject* o1 = swap ? sA.object : sB.object;
        // btManifoldResult's bodies are the pair's (the pair cache puts the lower proxy id first).
        const bool pairOrder = proxyId(o0) <= proxyId(o1);
        const btCollisionObject* c0 = pairOrder ? o0 : o1;
        const btCollisionObject* c1 = pairOrder ? o1 : o0;
        const bool flagged = gContactAddedCallback && ((o0->getCollisionFlags() | o1->getCollisionFlags()) &
                                                       btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
        // The device's own combination (prepare_contacts), to know what must be sent.
        const btScalar deviceFriction = btManifoldResult::calculateCombinedFriction(sA.object, sB.object);
        const btScalar deviceRestitution = sA.object->getRestitution() * sB.object->getRestitution();
        const int n = std::min(m.numPoints, int(BTG_MAX_POINTS));
        // A convex–concave pair's points carry their triangles' keys: its added points are named
        // by place (their identities would match by feature id points of one triangle alike).
        const bool byPosition = g.added != -2 && (unsigned(g.added) & BTG_ADDED_BY_POSITION) != 0u;
        // Stock's box–box algorithm (the dispatcher's for two btBoxShape leaves, a compound's
        // child boxes too: the GPU path requires Bullet's default algorithms) reports a point only
        // while the boxes overlap and only with depth >= 0 (dBoxBox2); a speculative device point
        // there is, on stock, an old point its refresh kept, not one added.
        const bool boxBox = sA.shape->getShapeType() == BOX_SHAPE_PROXYTYPE && sB.shape->getShapeType() == BOX_SHAPE_PROXYTYPE;
        // Each point as addContactPoint makes it (with the user data of the app's point it
        // continues, as replaceContactPoint keeps it), then the added callback on it.
        btManifoldPoint cps[BTG_MAX_POINTS], initial[BTG_MAX_POINTS];
        void* loaded[BTG_MAX_POINTS];
        btPersistentManifold* app = side.spheres ? nullptr : sync.manifold(side);
        int continues[BTG_MAX_POINTS];  // the app's point each device point continues, -1 for none
        for (int k = 0; k < n; ++k) {
            const BtgManifoldPoint& p = m.points[k];
            const btVector3 nrm(p.nx, p.ny, p.nz), pB(p.px, p.py, p.pz);
            const btScalar d = p.distance;
            const btVector3 pA = pB + nrm * d;
            const btVector3 normal = swap ? -nrm : nrm;
            const btVector3 onA = swap ? pB : pA, onB = swap ? pA : pB;
            btManifoldPoint& cp = cps[k];
            cp = btManifoldPoint(o0->getWorldTransform().invXform(onA), o1->getWorldTransform().invXform(onB), normal, d);
            cp.m_positionWorldOnA = onA;
            cp.m_positionWorldOnB = onB;
            cp.m_combinedFriction = gCalculateCombinedFrictionCallback(c0, c1);
            cp.m_combinedRestitution = gCalculateCombinedRestitutionCallback(c0, c1);
            cp.m_combinedRollingFriction = gCalculateCombinedRollingFrictionCallback(c0, c1);
            cp.m_combinedSpinningFriction = gCalculateCombinedSpinningFrictionCallback(c0, c1);
            btPlaneSpace1(cp.m_normalWorldOnB, cp.m_lateralFrictionDir1, cp.m_lateralFrictionDir2);
            // Rolling and spinning friction rows are not on the GPU path: a combiner that gives a
            // pair some cannot be served (Bullet's own gives 0 unless a body has them, a body rule).
            if (cp.m_combinedRollingFriction != 0 || cp.m_combinedSpinningFriction != 0) {
                m_reason = "a rolling or spinning friction combiner (gCalculateCombinedRolling/SpinningFrictionCallback) "
                           "gave a contact rolling or spinning friction, which the GPU path does not have";
                return false;
            }
            int partA = m.partIdA, indexA = m.indexA, partB = m.partIdB, indexB = m.indexB;
            // A concave side's wrapper holds the point's triangle, in the concave body's frame.
            btTriangleShape triA(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 0));
            btTriangleShape triB(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 0));
            for (int sd = 0; sd < 2; ++sd) {
                SideShape& ss = sd == 0 ? sA : sB;
                if (!ss.concave) continue;
                int& part = sd == 0 ? partA : partB;
                int& index = sd == 0 ? indexA : indexB;
                triangleOfFeature(ss.shape, p.featureId, &part, &index);
                if (!flagged) continue;
                btVector3 v[3];
                if (!findTriangle(ss.shape, ss.transform.invXform(sd == 0 ? pA : pB), part, index, v)) {
                    m_reason = std::string("gContactAddedCallback: a contact's triangle of '") + ss.shape->getName() +
                               "' was not found for its wrapper";
                    return false;
                }
                btTriangleShape& tri = sd == 0 ? triA : triB;
                tri = btTriangleShape(v[0], v[1], v[2]);
                tri.setMargin(ss.shape->getMargin());
            }
            cp.m_partId0 = swap ? partB : partA;
            cp.m_index0 = swap ? indexB : indexA;
            cp.m_partId1 = swap ? partA : partB;
            cp.m_index1 = swap ? indexA : indexB;
            // A point that replaces one keeps its user data, lifetime and impulses
            // (replaceContactPoint): those of the app's point it continues.
            bool oldMoved = false;
            const btManifoldPoint* old =
                sync.continued(side, p.featureId, cp.m_index0, cp.m_partId1, cp.m_index1, cp.m_localPointA, &oldMoved,
                               g.added != -2 && !byPosition);
            // Where a body is a compound, stock's compound algorithm refreshes the child manifold
            // before the child collides (ManifoldSync::refreshesPerStep): the old point, aged and
            // at this step's transforms, goes to the processed callback first, and the point that
            // replaces it keeps that lifetime and the user data the callback left.
            btManifoldPoint pre;
            bool preCalled = false;
            continues[k] = old && app ? int(old - &app->getContactPoint(0)) : -1;
            if (old) {
                pre = *old;
                pre.m_lifeTime += side.refreshes - 1;
                if (side.refreshes > 1 && gContactProcessedCallback) {
                    pre.m_positionWorldOnA = o0->getWorldTransform()(pre.m_localPointA);
                    pre.m_positionWorldOnB = o1->getWorldTransform()(pre.m_localPointB);
                    pre.m_distance1 = (pre.m_positionWorldOnA - pre.m_positionWorldOnB).dot(pre.m_normalWorldOnB);
                    const btScalar breaking = sync.manifold(side)->getContactBreakingThreshold();
                    const btVector3 drift =
                        pre.m_positionWorldOnB - (pre.m_positionWorldOnA - pre.m_normalWorldOnB * pre.m_distance1);
                    // Each refresh before the child collides calls it (two for nested compounds).
                    if (pre.m_distance1 <= breaking && drift.length2() <= breaking * breaking) {
                        for (int r = 1; r < side.refreshes; ++r) {
                            gContactProcessedCallback(pre, (void*)o0, (void*)o1);
                            ++m_calls;
                        }
                        preCalled = true;
                    }
                }
                cp.m_userPersistentData = pre.m_userPersistentData;
                cp.m_lifeTime = pre.m_lifeTime;
                cp.m_appliedImpulse = old->m_appliedImpulse;
                cp.m_appliedImpulseLateral1 = old->m_appliedImpulseLateral1;
                cp.m_appliedImpulseLateral2 = old->m_appliedImpulseLateral2;
                cp.m_prevRHS = old->m_prevRHS;
            }
            // A box–box point stock's detector would not report that continues one: stock's
            // solve uses the kept point as the callback left it when it was added (its friction
            // and restitution), and calls nothing for it. One that continues none is still
            // called: stock has no point there, and the device's new contact must be served. So
            // is one whose last callback moved its points: stock's kept point goes on from the
            // moved local points, the device's fresh one only through the callback again.
            // A GJK pair's manifold persists its points (stock's convex–convex algorithm adds one
            // a step): only the one this substep added or replaced is called; the others are kept
            // points, as the box–box ones above.
            const unsigned bit = byPosition ? unsigned(k) : (p.featureId & 7u);
            const bool persisted = g.added != -2 && !((unsigned(g.added) >> bit) & 1u);
            const bool kept = flagged && ((boxBox && p.distance > 0) || persisted) && old && !oldMoved;
            if (kept) {
                cp.m_combinedFriction = (preCalled ? pre : *old).m_combinedFriction;
                cp.m_combinedRestitution = (preCalled ? pre : *old).m_combinedRestitution;
            }
            loaded[k] = cp.m_userPersistentData;
            initial[k] = cp;
            if (!flagged || kept) continue;
            const btCollisionObjectWrapper wA(nullptr, sA.concave ? &triA : sA.shape, sA.object, sA.transform, partA, indexA);
            const btCollisionObjectWrapper wB(nullptr, sB.concave ? &triB : sB.shape, sB.object, sB.transform, partB, indexB);
            gContactAddedCallback(cp, swap ? &wB : &wA, cp.m_partId0, cp.m_index0, swap ? &wA : &wB, cp.m_partId1,
                                  cp.m_index1);
            ++m_calls;
        }
        // The refresh's processed callback: every point, from the last down, its lifetime counted
        // on (refreshContactPoints). Stock's sphere–sphere algorithm clears its manifold instead
        // and refreshes nothing.
        if (gContactProcessedCallback && !side.spheres)
            for (int k = n - 1; k >= 0; --k) {
                ++cps[k].m_lifeTime;
                gContactProcessedCallback(cps[k], (void*)o0, (void*)o1);
                ++m_calls;
            }
        // The app's old points no device point replaced: stock's refresh keeps them while within
        // the breaking threshold at these transforms and gives each to the processed callback,
        // aged (at each of its refreshes). Which stay is the fill's (refill's `retain`): the old
        // points, then the device's, a continued one in its old one's slot, a new one added with
        // Bullet's reduction choosing when four are held; replayed here on a scratch manifold.
        // What the callback sets on them stays on the app's point, for the fill; they are not in
        // the device's solve (nor were they before).
        const int oldCount = app ? app->getNumContacts() : 0;
        unsigned replaced = 0;  // the old points a device point takes the slot of
        int added = 0;          // the device points the fill adds (continuing none, or one already taken)
        for (int k = 0; k < n; ++k) {
            if (continues[k] >= 0 && !((replaced >> continues[k]) & 1u)) replaced |= 1u << continues[k];
            else ++added;
        }
        // A persistent manifold (g.added != -2) is the device's own refresh: it holds every point
        // stock's would.
        if (gContactProcessedCallback && g.added == -2 && oldCount > 0 && n > 0 && replaced != (1u << oldCount) - 1) {
            int order[MANIFOLD_CACHE_SIZE], numKept = 0;  // old points the fill keeps, last slot first
            if (oldCount + added <= MANIFOLD_CACHE_SIZE) {
                // Room for all: no reduction, the old points stay in their slots.
                for (int j = oldCount - 1; j >= 0; --j)
                    if (!((replaced >> j) & 1u)) order[numKept++] = j;
            } else {
                btPersistentManifold scratch(o0, o1, 0, app->getContactBreakingThreshold(), app->getContactProcessingThreshold());
                for (int j = 0; j < oldCount; ++j) {
                    btManifoldPoint q = app->getContactPoint(j);
                    q.m_userPersistentData = nullptr;
                    q.m_lifeTime = j;
                    scratch.addManifoldPoint(q, true);
                }
                for (int k = 0; k < n; ++k) {
                    btManifoldPoint q = cps[k];
                    q.m_userPersistentData = nullptr;
                    q.m_lifeTime = -1 - k;
                    int slot = -1;
                    for (int sl = 0; continues[k] >= 0 && sl < scratch.getNumContacts() && slot < 0; ++sl)
                        if (scratch.getContactPoint(sl).m_lifeTime == continues[k]) slot = sl;
                    if (slot >= 0) scratch.getContactPoint(slot) = q;
                    else scratch.addManifoldPoint(q, true);
                }
                // Where the reduction dropped a device point for an old one, the callback had that
                // device point (it is in the device's solve, which needs its coefficients): the old
                // one is not called, so that no more points are called than the manifold holds.
                int devicePoints = 0;
                for (int sl = 0; sl < scratch.getNumContacts(); ++sl) devicePoints += scratch.getContactPoint(sl).m_lifeTime < 0;
                for (int sl = scratch.getNumContacts() - 1; sl >= 0 && devicePoints == n; --sl)
                    if (scratch.getContactPoint(sl).m_lifeTime >= 0) order[numKept++] = scratch.getContactPoint(sl).m_lifeTime;
                scratch.setNumContacts(0);
            }
            const btScalar breaking = app->getContactBreakingThreshold();
            for (int o = 0; o < numKept; ++o) {
                btManifoldPoint& op = app->getContactPoint(order[o]);
                btManifoldPoint q = op;
                q.m_positionWorldOnA = o0->getWorldTransform()(q.m_localPointA);
                q.m_positionWorldOnB = o1->getWorldTransform()(q.m_localPointB);
                q.m_distance1 = (q.m_positionWorldOnA - q.m_positionWorldOnB).dot(q.m_normalWorldOnB);
                const btVector3 drift = q.m_positionWorldOnB - (q.m_positionWorldOnA - q.m_normalWorldOnB * q.m_distance1);
                if (q.m_distance1 > breaking || drift.length2() > breaking * breaking) continue;
                for (int r = 0; r < side.refreshes; ++r) {
                    ++q.m_lifeTime;
                    gContactProcessedCallback(q, (void*)o0, (void*)o1);
                    ++m_calls;
                }
                op.m_userPersistentData = q.m_userPersistentData;
                op.m_combinedFriction = q.m_combinedFriction;
                op.m_combinedRestitution = q.m_combinedRestitution;
            }
        }
        BtgManifold out = m;
        BtgContactMaterial material{};
        material.slot = g.slot;
        bool geometry = false, needMaterial = false;
        for (int k = 0; k < n; ++k) {
            const btManifoldPoint& cp = cps[k];
            const btManifoldPoint& before = initial[k];
            const char* uncarried = uncarriedChange(cp, before);
            if (*uncarried) {
                m_reason = std::string("a contact callback (gContactAddedCallback or gContactProcessedCallback) changed ") +
                           uncarried + " of a contact point, which the GPU path does not carry";
                return false;
            }
            // Friction: the device's contact has one coefficient for its points.
            if (k == 0) material.friction = cp.m_combinedFriction;
            else if (cp.m_combinedFriction != material.friction) {
                m_reason = "a contact callback or the friction combiner set different friction on the points of one "
                           "contact manifold (the GPU path's contact has one coefficient)";
                return false;
            }
            btgSetLane(&material.restitution, k, cp.m_combinedRestitution);
            needMaterial |= cp.m_combinedFriction != deviceFriction || cp.m_combinedRestitution != deviceRestitution;
            const bool moved = !(sameVec(cp.m_normalWorldOnB, before.m_normalWorldOnB) &&
                                 sameVec(cp.m_positionWorldOnA, before.m_positionWorldOnA) &&
                                 sameVec(cp.m_positionWorldOnB, before.m_positionWorldOnB) &&
                                 cp.m_distance1 == before.m_distance1);
            if (cp.m_userPersistentData || loaded[k] || flagged || all)
                sync.setPointState({m.bodyA, m.bodyB, m.indexA, m.indexB, m.points[k].featureId, k},
                                   {cp.m_userPersistentData, cp.m_combinedFriction, cp.m_combinedRestitution, moved});
            if (!moved) continue;
            // The device keeps the point on B, the normal and the distance (the point on A is
            // implied): the callback's points must keep that relation, its normal unit.
            const btVector3 implied = cp.m_positionWorldOnB + cp.m_normalWorldOnB * cp.m_distance1;
            const btScalar tol = btScalar(1e-5) * (1 + cp.m_positionWorldOnA.length());
            if ((implied - cp.m_positionWorldOnA).length() > tol || std::fabs(cp.m_normalWorldOnB.length() - 1) > 1e-4f) {
                m_reason = "a contact callback moved a contact's points apart from its normal and distance "
                           "(the GPU path keeps the point on B, the normal and the distance)";
                return false;
            }
            const btVector3 nOut = swap ? -cp.m_normalWorldOnB : cp.m_normalWorldOnB;
            const btVector3 pOut = swap ? cp.m_positionWorldOnA : cp.m_positionWorldOnB;
            BtgManifoldPoint& q = out.points[k];
            q.px = pOut.x();
            q.py = pOut.y();
            q.pz = pOut.z();
            q.nx = nOut.x();
            q.ny = nOut.y();
            q.nz = nOut.z();
            q.distance = cp.m_distance1;
            geometry = true;
        }
        if (geometry) {
            // The device's contact has one normal (its first point's): the points' must agree, to
            // within the rounding a GJK manifold's own points show (each keeps the normal of the
            // step that added it: 2e-5 apart on a box resting on a mesh, where
            // btAdjustInternalEdgeContacts snapped one point's to the triangle's exact normal and
            // 1e-5 sent the world to the CPU path). An edge the callback turns a normal away from
            // is degrees, far beyond this.
            constexpr float kSameNormal = 1e-4f;
            for (int k = 1; k < n; ++k) {
                const BtgManifoldPoint &a = out.points[0], &b = out.points[k];
                if (std::fabs(a.nx - b.nx) > kSameNormal || std::fabs(a.ny - b.ny) > kSameNormal ||
                    std::fabs(a.nz - b.nz) > kSameNormal) {
                    m_reason = "a contact callback gave the points of one contact manifold different normals (the "
                               "GPU path's contact has one normal)";
                    return false;
                }
            }
            m_changed.push_back({g.slot, out});
        }
        if (needMaterial) m_materials.push_back(material);
    }
    sendCallbackChanges(w, m_changed, m_materials);
    return true;
}

}  // namespace btgpu
