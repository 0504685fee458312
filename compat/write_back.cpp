// write_back.cpp — after a device call, the results into the app's bodies as stock Bullet leaves
// them: transforms, velocities, activation and sleeping state, bodies the device found bad (the
// part of GpuWorld that writes to the app's objects).
#include "gpu_world.h"

#include "body_rows.h"
#include "parallel_rows.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace btgpu {

void GpuWorld::writeBack(const BodyReadback& rb, bool last, bool sleepRead)
{
    // Rows are independent Bullet objects: written in parallel; what needs the world (issues,
    // motion states of bodies that fell asleep) is collected per chunk and done after, in order.
    // On the last write-back of a call, when the world is exactly btGpuDynamicsWorld (so its
    // synchronizeMotionStates and clearForces are ours), the same pass also does their work for
    // each body: Bullet's own motion states and the force clear, touching each body once. Not
    // with an internal tick callback, which Bullet runs before both and which may read them.
    const bool fuse = last && typeid(m_world) == typeid(btGpuDynamicsWorld) &&
                      !m_world.m_synchronizeAllMotionStates && !m_world.m_internalTickCallback;
    const size_t n = m_rows.size();
    const size_t minPerThread = kBodyRowsPerThread;
    const int chunks = chunkCount(n, minPerThread);
    std::vector<std::vector<size_t>> bad(chunks), fellAsleep(chunks);
    forEachChunk(n, minPerThread, [&](size_t begin, size_t end, int chunk) {
        for (size_t r = begin; r < end; ++r) {
            // the body a few rows ahead, and the motion state of the next but one (whose body
            // came two rows ago), fetched while this one is written (objects scattered over
            // the heap); not while bodies removed inside this call may be gone
            if (m_removed.empty()) {
                if (r + 4 < end)
                    if (const btCollisionObject* ahead = m_rows.at(r + 4)) prefetchObject(ahead, sizeof(btRigidBody), true);
                if (fuse && r + 2 < end)
                    if (const btRigidBody* next = m_rows.at(r + 2) ? btRigidBody::upcast(m_rows.at(r + 2)) : nullptr)
                        if (const btMotionState* ms = next->getMotionState()) prefetchObject(ms, sizeof(btDefaultMotionState), true);
            }
            btCollisionObject* o = m_rows.at(r);
            if (!m_removed.empty() && m_removed.count(o)) continue;  // removed inside this call
            btRigidBody* body = o ? btRigidBody::upcast(o) : nullptr;
            if (!body) continue;
            bool asleepNow = writeRow(r, body, rb, sleepRead, &bad[chunk]);
            if (!fuse) {
                if (asleepNow) fellAsleep[chunk].push_back(r);
                continue;
            }
            if (!body->isStaticObject()) body->clearForces();
            // Bullet's synchronizeMotionStates visits the active non-static bodies; a body that
            // fell asleep in this step gets its last move too (see below).
            btMotionState* ms = body->getMotionState();
            bool visit = body->isActive() || asleepNow;
            if (ms && visit && !body->isStaticOrKinematicObject()) {
                if (typeid(*ms) == typeid(btDefaultMotionState)) m_world.synchronizeSingleMotionState(body);
                else if (asleepNow) fellAsleep[chunk].push_back(r);  // the app's own: serially, below
            }
        }
    });
    m_fusedWriteBack = fuse;
    for (const std::vector<size_t>& rows : bad)
        for (size_t r : rows) {
            btCollisionObject* body = m_rows.at(r);
            int index = m_world.getCollisionObjectArray().findLinearSearch(body);
            report({Issue::Kind::BadBody,
                    "body " + std::to_string(index) + " (user index " + std::to_string(body->getUserIndex()) +
                        ") became non-finite on the device; its last good state is kept",
                    index, body->getUserIndex(), body->getCollisionShape()->getShapeType()});
        }
    // Stock Bullet stops a body before its island sleeps; these moved in the step they fell
    // asleep, and synchronizeMotionStates skips sleeping bodies: their motion states get that
    // last move here.
    for (const std::vector<size_t>& rows : fellAsleep)
        for (size_t r : rows) m_world.synchronizeSingleMotionState(btRigidBody::upcast(m_rows.at(r)));
}

bool GpuWorld::writeRow(size_t r, btRigidBody* body, const BodyReadback& rb, bool sleepRead, std::vector<size_t>* bad)
{
    Mirror& m = m_mirror[r];
    uint f = m.props.flags;
    if (!(f & BTG_BODY_DYNAMIC) || (f & BTG_BODY_EXCLUDED)) return false;
    bool wasAsleep = (f & BTG_BODY_SLEEPING) != 0;
    // Before the deactivation ran (actions in between) the sleep states are not this step's.
    bool asleep = sleepRead ? rb.sleepState[r] != 0 : wasAsleep;
    if (wasAsleep && asleep) {  // nothing moved
        if (m.touchedAsleep && sleepRead) settleSleeper(body, m);  // after the deactivation, as stock
        return false;
    }
    BtgFloat4 p = rb.pos[r], q = rb.rot[r], v = rb.linVel[r], a = rb.angVel[r];
    if (!btgIsFinite4(p) || !btgIsFinite4(q) || !btgIsFinite4(v) || !btgIsFinite4(a)) {
        bad->push_back(r);
        m.props.flags = 0xffffffffu;  // forces the good state back up next call
        return false;
    }
    body->setLinearVelocity(btVector3(v.x, v.y, v.z));
    body->setAngularVelocity(btVector3(a.x, a.y, a.z));
    // As Bullet's integrateTransforms → proceedToTransform: also sets the interpolation
    // transform and velocities that synchronizeMotionStates extrapolates from.
    body->setCenterOfMassTransform(btTransform(btQuaternion(q.x, q.y, q.z, q.w), btVector3(p.x, p.y, p.z)));
    if (asleep) {
        body->setActivationState(ISLAND_SLEEPING);
        m.props.flags |= BTG_BODY_SLEEPING;
    } else if (wasAsleep) {
        body->setActivationState(ACTIVE_TAG);
        body->setDeactivationTime(0);
        m.props.flags &= ~BTG_BODY_SLEEPING;
    }
    // The device's own timer, as stock's updateDeactivation leaves m_deactivationTime (read by
    // apps; the next call sees the app's activate() by it)
    if (sleepRead) body->setDeactivationTime(rb.sleepTime[r]);
    m.deactivation = body->getDeactivationTime();
    m.xf = body->getWorldTransform();
    m.linVel = body->getLinearVelocity();
    m.angVel = body->getAngularVelocity();
    return asleep;
}

void GpuWorld::settleSleeper(btRigidBody* body, Mirror& m)
{
    // Stock's step for a sleeping body (predictUnconstraintMotion, then updateActivationState):
    // damped, its interpolation transform predicted from where the app put it (which
    // synchronizeMotionStates reads with setSynchronizeAllMotionStates), then, while
    // deactivation is on, its velocities zeroed (apply_sleep zeroes the device's copy).
    const bool moving = !(body->getLinearVelocity() == btVector3(0, 0, 0)) || !(body->getAngularVelocity() == btVector3(0, 0, 0));
    m.touchedAsleep = false;
    // With deactivation off the velocities stay (the device keeps its copy as it is: no damping
    // here either, so the two agree).
    const bool zeroed = !gDisableDeactivation && gDeactivationTime != btScalar(0);
    if (zeroed) body->applyDamping(m_stepDt);
    btTransform predicted;
    body->predictIntegratedTransform(m_stepDt, predicted);
    body->setInterpolationWorldTransform(predicted);
    if (!zeroed) return;
    body->setLinearVelocity(btVector3(0, 0, 0));
    body->setAngularVelocity(btVector3(0, 0, 0));
    m.linVel = m.angVel = btVector3(0, 0, 0);
    // The next step predicts from rest: the interpolation transform back on the body then.
    m.touchedAsleep = moving;
}

bool GpuWorld::takeFusedWriteBack()
{
    bool fused = m_fusedWriteBack;
    m_fusedWriteBack = false;
    return fused;
}

}  // namespace btgpu
