// report_contacts_test.cpp — the contact report: on the device, each contact's record is the
// reference's (bodies, sub-shape keys, counts and feature ids exactly; points, frames and
// impulses within kStageAbs / kStageRel), a count past capacity is clamped, and slots past the
// count are left untouched; the same where they lie over the soft step's rows.
#include "reference/report_contacts.h"
#include "stages/report_contacts.h"
#include "test_device.h"
#include "tolerances.h"

#include <cmath>
#include <gtest/gtest.h>
#include <random>

using namespace btgpu;
using btgpu::tol::kStageAbs;
using btgpu::tol::kStageRel;

namespace {

void expectNear4(BtgFloat4 a, BtgFloat4 b, const char* what, int i, int k)
{
    const float ta = kStageAbs + kStageRel * std::fabs(b.x), tb = kStageAbs + kStageRel * std::fabs(b.y);
    const float tc = kStageAbs + kStageRel * std::fabs(b.z), td = kStageAbs + kStageRel * std::fabs(b.w);
    EXPECT_NEAR(a.x, b.x, ta) << what << " " << i << " " << k;
    EXPECT_NEAR(a.y, b.y, tb) << what << " " << i << " " << k;
    EXPECT_NEAR(a.z, b.z, tc) << what << " " << i << " " << k;
    EXPECT_NEAR(a.w, b.w, td) << what << " " << i << " " << k;
}

}  // namespace

TEST(ReportContacts, DeviceMatchesReference)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const int numBodies = 20, slots = 60, numContacts = 45, capacity = 50;
    std::vector<BtgFloat4> pos(numBodies), rot(numBodies);
    for (int i = 0; i < numBodies; ++i) {
        pos[i] = btgMake4(5 * u(rng), 5 * u(rng), 5 * u(rng), 0);
        rot[i] = btgQuatNormalize(btgMake4(u(rng), u(rng), u(rng), u(rng)));
    }
    std::vector<BtgManifold> manifolds(slots);
    for (int s = 0; s < slots; ++s) {
        BtgManifold& m = manifolds[s];
        m = BtgManifold{};
        m.bodyA = int(rng() % numBodies);
        m.bodyB = (m.bodyA + 1 + int(rng() % (numBodies - 1))) % numBodies;
        m.numPoints = 1 + int(rng() % BTG_MAX_POINTS);
        m.partIdA = -1;
        m.indexA = int(rng() % 5) - 1;
        m.partIdB = int(rng() % 3);
        m.indexB = int(rng() % 1000);
        m.breakingThreshold = 0.02f;
        BtgFloat4 n = btgNormalize3(btgMake4(u(rng), u(rng), u(rng), 0));
        for (int k = 0; k < m.numPoints; ++k) {
            BtgManifoldPoint& p = m.points[k];
            p.px = pos[m.bodyB].x + u(rng);
            p.py = pos[m.bodyB].y + u(rng);
            p.pz = pos[m.bodyB].z + u(rng);
            p.distance = 0.02f * u(rng);
            p.nx = n.x;
            p.ny = n.y;
            p.nz = n.z;
            p.featureId = rng();
        }
    }
    std::vector<BtgContact> contacts(capacity);
    std::vector<uint> contactManifolds(capacity);
    for (int i = 0; i < capacity; ++i) {
        const uint slot = uint(rng() % slots);
        contactManifolds[i] = slot;
        const BtgManifold& m = manifolds[slot];
        BtgContact c = btgContactFromManifold(m, pos[m.bodyA], pos[m.bodyB]);
        btgPlaneSpace(c.normal, &c.tangent1, &c.tangent2);
        for (int k = 0; k < m.numPoints; ++k) {
            const float angle = 3.0f * u(rng);
            btgSetLane(&c.frictionCos, k, std::cos(angle));
            btgSetLane(&c.frictionSin, k, std::sin(angle));
            btgSetLane(&c.normalImpulse, k, 1 + u(rng));
            btgSetLane(&c.friction1Impulse, k, u(rng));
            btgSetLane(&c.friction2Impulse, k, u(rng));
        }
        contacts[i] = c;
    }

    DeviceWorld w(test::context());
    w.contactCapacity = size_t(capacity);
    w.contacts.upload(w.ctx, contacts);
    w.contactManifolds.upload(w.ctx, contactManifolds);
    w.manifolds.upload(w.ctx, manifolds);
    w.pos.upload(w.ctx, pos);
    w.rot.upload(w.ctx, rot);
    std::vector<uint> counters(kNumCounters, 0u);
    // The soft step's reports lie over its rows' storage (dead after its solve), with no buffer
    // of their own: the same reports there.
    for (bool overSoftRows : {false, true})
    for (int count : {numContacts, capacity + 30}) {  // the second past capacity: clamped
        SCOPED_TRACE(overSoftRows ? "over the soft rows" : "own buffer");
        counters[kContactCount] = uint(count);
        w.counters.upload(w.ctx, counters);
        std::vector<BtgContactReport> sentinel(capacity);
        for (BtgContactReport& r : sentinel) r.bodyA = -7;
        if (overSoftRows) {
            w.solverScratch.rowsAs<BtgContactReport>(w.ctx, capacity).upload(w.ctx, sentinel);
        } else {
            w.contactReports.reserveExact(w.ctx, capacity);
            w.contactReports.upload(w.ctx, sentinel);
        }
        w.contactReportsWritten = false;
        reportContacts(w, overSoftRows);
        EXPECT_TRUE(w.contactReportsWritten);
        EXPECT_EQ(w.reports.capacity(), size_t(capacity));
        if (overSoftRows) {
            EXPECT_EQ(w.contactReports.capacity(), 0u);
            EXPECT_EQ(w.reports.mem(), w.solverScratch.softContacts.mem());
        }
        const int n = std::min(count, capacity);
        std::vector<BtgContactReport> got = w.reports.download(w.ctx, capacity);
        std::vector<BtgContact> used(contacts.begin(), contacts.begin() + n);
        std::vector<uint> usedManifolds(contactManifolds.begin(), contactManifolds.begin() + n);
        std::vector<BtgContactReport> want = ref::reportContacts(used, usedManifolds, manifolds, pos, rot);
        for (int i = 0; i < n; ++i) {
            const BtgContactReport &g = got[i], &e = want[i];
            EXPECT_EQ(g.bodyA, e.bodyA) << i;
            EXPECT_EQ(g.bodyB, e.bodyB) << i;
            EXPECT_EQ(g.numPoints, e.numPoints) << i;
            EXPECT_EQ(g.partIdA, e.partIdA) << i;
            EXPECT_EQ(g.indexA, e.indexA) << i;
            EXPECT_EQ(g.partIdB, e.partIdB) << i;
            EXPECT_EQ(g.indexB, e.indexB) << i;
            for (int k = 0; k < BTG_MAX_POINTS; ++k) {
                EXPECT_EQ(g.featureId[k], e.featureId[k]) << i << " " << k;
                expectNear4(g.pointB[k], e.pointB[k], "pointB", i, k);
                expectNear4(g.normal[k], e.normal[k], "normal", i, k);
                expectNear4(g.localA[k], e.localA[k], "localA", i, k);
                expectNear4(g.localB[k], e.localB[k], "localB", i, k);
                expectNear4(g.dir1[k], e.dir1[k], "dir1", i, k);
            }
            // The reference itself: local points are the world points in each body's frame.
            const BtgManifold& m = manifolds[contactManifolds[i]];
            for (int k = 0; k < m.numPoints; ++k) {
                BtgFloat4 back = btgQuatRotate(rot[m.bodyB], btgXyz(e.localB[k])) + btgXyz(pos[m.bodyB]);
                EXPECT_NEAR(back.x, m.points[k].px, 1e-4f);
                EXPECT_NEAR(e.localA[k].w, btgLane(contacts[i].normalImpulse, k), 0.0f);
            }
        }
        for (int i = n; i < capacity; ++i) EXPECT_EQ(got[i].bodyA, -7) << i;
    }
}
