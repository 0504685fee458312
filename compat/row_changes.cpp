// row_changes.cpp — what the app changed between steps, found without a rebuild: objects added
// and removed (rows followed), collision shapes swapped, and the rows whose Bullet state differs
// from the device's mirror (compared in parallel; bad input named), for the next call's sync-in.
#include "gpu_world.h"

#include "body_rows.h"
#include "cpu_path_rules.h"
#include "parallel_rows.h"
#include "shared/integrate.h"
#include "stages/narrowphase_gjk.h"
#include "stages/sync_bodies.h"

#include <algorithm>
#include <cstring>

namespace btgpu {

namespace {

bool sameTransform(const btTransform& a, const btTransform& b)
{
    const btVector3 &o1 = a.getOrigin(), &o2 = b.getOrigin();
    if (o1.x() != o2.x() || o1.y() != o2.y() || o1.z() != o2.z()) return false;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (a.getBasis()[r][c] != b.getBasis()[r][c]) return false;
    return true;
}

bool sameVec(const btVector3& a, const btVector3& b) { return a.x() == b.x() && a.y() == b.y() && a.z() == b.z(); }

BtgFloat4 finiteOrZero(BtgFloat4 v) { return btgIsFinite4(v) ? v : btgZero4(); }

}  // namespace

void GpuWorld::followRows()
{
    DeviceWorld& w = *m_dev;
    const RowMap::Changes changes = m_rows.follow(m_world.getCollisionObjectArray(), m_removed);
    m_removed.clear();
    m_rowsStale = false;
    // Retired rows are cheap (every stage skips them) but not free: past as many as there are
    // bodies, and past the unused shape rows' worth, every row is rebuilt densely.
    if (m_rows.unused() > std::max<size_t>(1024, m_rows.live()) ||
        m_shapes.unreferenced() > std::max<size_t>(64, m_shapes.shapes.size() / 2)) {
        rebuild();
        return;
    }
    const size_t n = m_rows.size();
    resizeBodies(w, int(n));  // keeps every row's contents
    if (m_shapes.takeGrown()) uploadShapeTables(true);
    makePlan();
    reservePairsAndContacts(n, true);  // the untouched pairs warm-start
    const size_t had = m_mirror.size();
    m_mirror.resize(n);
    for (size_t r = had; r < n; ++r) m_mirror[r] = Mirror::fresh();
    // A retired row takes no part in anything; a fresh one starts with its timers cleared and
    // is written whole by the next comparison (its mirror can match nothing).
    BodyRowUploads retired;
    for (size_t r : changes.retired) retired.add(retireRow(r));
    syncIn(w, retired);
    std::vector<int> fresh;
    for (size_t r : changes.fresh) {
        m_mirror[r] = Mirror::fresh();
        m_mirror[r].props.flags = 0xffffffffu;
        fresh.push_back(int(r));
    }
    resetRows(w, fresh, false);
}

bool GpuWorld::shapesSwapped() const
{
    const btCollisionObjectArray& objs = m_world.getCollisionObjectArray();
    const size_t n = size_t(objs.size());
    if (n != m_shapeOfObject.size()) return true;
    const size_t minPerThread = 8192;
    std::vector<char> swapped(size_t(chunkCount(n, minPerThread)), 0);
    forEachChunk(n, minPerThread, [&](size_t begin, size_t end, int chunk) {
        for (size_t i = begin; i < end; ++i) {
            // each object's shape pointer is on a line of its own, objects scattered over the
            // heap: fetched a few bodies ahead (bodiesReason reads the same line next)
            if (i + 8 < end) __builtin_prefetch(reinterpret_cast<const char*>(objs[int(i + 8)]) + 200);
            if (objs[int(i)]->getCollisionShape() != m_shapeOfObject[i]) {
                swapped[size_t(chunk)] = 1;
                return;
            }
        }
    });
    return std::find(swapped.begin(), swapped.end(), 1) != swapped.end();
}

BodyRowUpdate GpuWorld::retireRow(size_t r)
{
    BodyRowUpdate u{};
    u.row = int(r);
    u.rot = btgMake4(0, 0, 0, 1);
    u.props.flags = BTG_BODY_EXCLUDED;
    m_mirror[r] = Mirror::fresh();
    m_mirror[r].props = u.props;
    return u;
}

void GpuWorld::reportNewlyBad(const std::vector<std::vector<std::pair<size_t, std::string>>>& newlyBad)
{
    for (const auto& list : newlyBad)
        for (const auto& [r, bad] : list) {
            btCollisionObject* o = m_rows.at(r);
            int index = m_world.getCollisionObjectArray().findLinearSearch(o);
            report({Issue::Kind::BadBody,
                    "body " + std::to_string(index) + " (user index " + std::to_string(o->getUserIndex()) + ", shape " +
                        o->getCollisionShape()->getName() + "): " + bad + "; kept out of the simulation until fixed",
                    index, o->getUserIndex(), o->getCollisionShape()->getShapeType()});
        }
}

BodyRowUploads GpuWorld::changedRows()
{
    // Every row is compared with what the device holds (impulses and forces set between steps
    // leave no other trace). Rows are independent: compared in parallel chunks, each with its
    // own update list, merged in row order so the upload does not depend on thread timing.
    const size_t n = m_rows.size();
    const size_t minPerThread = kBodyRowsPerThread;
    const int chunks = chunkCount(n, minPerThread);
    std::vector<BodyRowUploads> found(static_cast<size_t>(chunks));
    m_woken.assign(n, 0);
    m_reshaped.assign(n, 0);
    m_timerSet.assign(n, 0);
    m_timerValue.resize(n);
    std::vector<std::vector<std::pair<size_t, std::string>>> newlyBad(static_cast<size_t>(chunks));
    forEachChunk(n, minPerThread, [&](size_t begin, size_t end, int chunk) {
        for (size_t r = begin; r < end; ++r) {
            // compareRow reads most of each body (objects scattered over the heap): the body a
            // few rows ahead fetched meanwhile, so the comparison stops waiting for memory
            if (r + 4 < end)
                if (const btCollisionObject* ahead = m_rows.at(r + 4)) prefetchObject(ahead, sizeof(btRigidBody), false);
            // Removed inside this call (by an action or a tick callback): the row follows at
            // the next internal step; the object may be gone already.
            if (!m_removed.empty() && m_removed.count(m_rows.at(r))) continue;
            BodyRowUpdate u;
            std::string bad;
            if (!compareRow(r, false, &u, &bad)) continue;
            if (!bad.empty()) newlyBad[size_t(chunk)].emplace_back(r, std::move(bad));
            found[size_t(chunk)].add(u);
        }
    });
    reportNewlyBad(newlyBad);
    BodyRowUploads out;
    size_t total = 0;
    for (const auto& list : found) total += list.size();
    out.rows.reserve(total);
    out.states.reserve(6 * total);
    out.props.reserve(total);
    for (const auto& list : found) out.append(list);
    return out;
}

BodyColumns GpuWorld::everyRow()
{
    // The rebuild's: every row written at its own index, its mirror started fresh there, in
    // parallel chunks, into arrays sized without writing them, so each page of the 1,000,000
    // rows is first touched by the chunk that fills it; no lists to merge, and the columns go
    // to the device as they are (no staging copy, no scatter).
    const size_t n = m_rows.size();
    const size_t minPerThread = kBodyRowsPerThread;
    BodyColumns cols;
    cols.resize(n);
    m_woken.assign(n, 0);
    m_reshaped.assign(n, 0);
    m_timerSet.assign(n, 0);
    m_timerValue.resize(n);
    std::vector<std::vector<std::pair<size_t, std::string>>> newlyBad(size_t(chunkCount(n, minPerThread)));
    forEachChunk(n, minPerThread, [&](size_t begin, size_t end, int chunk) {
        for (size_t r = begin; r < end; ++r) {
            m_mirror[r] = Mirror::fresh();
            if (r + 4 < end)
                if (const btCollisionObject* ahead = m_rows.at(r + 4)) prefetchObject(ahead, sizeof(btRigidBody), false);
            BodyRowUpdate u;
            std::string bad;
            if (!compareRow(r, true, &u, &bad)) u = retireRow(r);  // no object (none after a rebuild's reset)
            if (!bad.empty()) newlyBad[size_t(chunk)].emplace_back(r, std::move(bad));
            cols.set(r, u);
        }
    });
    reportNewlyBad(newlyBad);
    return cols;
}

void GpuWorld::afterSyncIn()
{
    std::vector<int> rows;
    for (size_t r = 0; r < m_woken.size(); ++r)
        if (m_woken[r]) rows.push_back(int(r));
    m_woken.clear();
    resetRows(*m_dev, rows, true);
    uploadTimers();
    rows.clear();
    for (size_t r = 0; r < m_reshaped.size(); ++r)
        if (m_reshaped[r]) rows.push_back(int(r));
    m_reshaped.clear();
    forgetConcaveManifolds(*m_dev, rows);
}

void GpuWorld::uploadTimers()
{
    std::vector<int> rows;
    std::vector<float> times;
    for (size_t r = 0; r < m_timerSet.size(); ++r)
        if (m_timerSet[r]) {
            rows.push_back(int(r));
            times.push_back(m_timerValue[r]);
        }
    m_timerSet.clear();
    setSleepTimes(*m_dev, rows, times);
}

bool GpuWorld::compareRow(size_t r, bool all, BodyRowUpdate* u, std::string* newlyBad)
{
    btCollisionObject* o = m_rows.at(r);
    if (!o) return false;  // retired: written once when it was
    Mirror& m = m_mirror[r];
    int shapeRow = m_shapes.rowOf.at(o->getCollisionShape());
    std::string bad = badInput(o);
    if (bad.empty() && !m_shapes.badReason[size_t(shapeRow)].empty()) bad = "shape: " + m_shapes.badReason[size_t(shapeRow)];
    if (bad.empty() && aabbOverflows(o, m_shapes.shapes[size_t(shapeRow)], m_stepDt, m_world.getDispatchInfo().m_useContinuous)) {
        // What stock Bullet does to such a body (and all it does to the app's object).
        o->setActivationState(DISABLE_SIMULATION);
        bad = "AABB 1e6 m or more across: removed from the simulation (DISABLE_SIMULATION), as stock Bullet does";
    }
    bool excluded = !bad.empty();
    BtgBodyProps props = bodyProps(o, shapeRow, m_shapes.shapes[shapeRow], excluded);
    if (m_large[r]) props.flags |= BTG_BODY_LARGE;  // paired by the large pass, not the grid
    if (r < m_heldAwake.size() && m_heldAwake[r]) props.flags |= BTG_BODY_NEVER_SLEEP;  // in a ghost's island
    // With an app's overlap filter Bullet's pair cache decides the pairs, not group and mask.
    if (m_overlapFilter) props.group = props.mask = -1;
    const btRigidBody* rb = btRigidBody::upcast(o);
    btVector3 lin = rb ? rb->getLinearVelocity() : btVector3(0, 0, 0);
    btVector3 ang = rb ? rb->getAngularVelocity() : btVector3(0, 0, 0);
    btVector3 force = rb ? rb->getTotalForce() : btVector3(0, 0, 0);
    btVector3 torque = rb ? rb->getTotalTorque() : btVector3(0, 0, 0);
    // The app's activate() zeroes the body's deactivation timer (stock keeps a slow body awake
    // that way); the device's timer follows any value the app set (a rebuild: every timer but 0,
    // the device's start).
    const float deactivation = o->getDeactivationTime();
    if ((all && deactivation != 0.0f) || (!all && deactivation != m.deactivation)) {
        m_timerSet[r] = 1;
        m_timerValue[r] = deactivation;
    }
    m.deactivation = deactivation;
    bool changed = all || excluded != m.excluded || std::memcmp(&props, &m.props, sizeof(props)) != 0 ||
                   !sameTransform(o->getWorldTransform(), m.xf) || !sameVec(lin, m.linVel) || !sameVec(ang, m.angVel) ||
                   !sameVec(force, m.force) || !sameVec(torque, m.torque);
    if (!changed) return false;
    if (excluded && !m.excluded) *newlyBad = bad;
    if (!all && m.props.flags != 0xffffffffu && (m.props.flags & BTG_BODY_SLEEPING) && !(props.flags & BTG_BODY_SLEEPING))
        m_woken[r] = 1;
    // A mesh or heightfield the app edited in place is read again into a new row: the points the
    // device keeps against the old surface go, as stock's go when the app cleans the pair (it
    // must: its manifolds too hold the old surface's points) or the pair's AABBs part.
    if (m.props.flags != 0xffffffffu && m.props.shape != props.shape &&
        btgIsConcave(m_shapes.shapes[size_t(shapeRow)].type))
        m_reshaped[r] = 1;
    BodyState s = bodyState(o);
    u->row = int(r);
    u->pos = finiteOrZero(s.pos);
    u->rot = btgIsFinite4(s.rot) ? s.rot : btgMake4(0, 0, 0, 1);
    u->linVel = finiteOrZero(s.linVel);
    u->angVel = finiteOrZero(s.angVel);
    u->force = finiteOrZero(s.force);
    u->torque = finiteOrZero(s.torque);
    u->props = props;
    m.xf = o->getWorldTransform();
    m.linVel = lin;
    m.angVel = ang;
    m.force = force;
    m.torque = torque;
    m.props = props;
    m.excluded = excluded;
    m.touchedAsleep = (props.flags & BTG_BODY_SLEEPING) && (props.flags & BTG_BODY_DYNAMIC) && rb;
    return true;
}

}  // namespace btgpu
