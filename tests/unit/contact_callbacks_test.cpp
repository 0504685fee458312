// contact_callbacks_test.cpp — the contact-callback stage against its CPU reference: the gather
// finds exactly the flagged pairs' manifolds (in slot order, also past its first buffer), the
// scatter puts the host's changes at their slots, and the materials' second preparation is the
// reference's (within kStageAbs / kStageRel), touches only the contacts it names, equals the
// first preparation when the material is the bodies' own, and is used once.
#include "contact_fixture.h"
#include "reference/contact_callbacks.h"
#include "stages/contact_callbacks.h"
#include "test_device.h"
#include "tolerances.h"

#include <cstring>
#include <gtest/gtest.h>

using namespace btgpu;
using btgpu::tol::kStageAbs;
using btgpu::tol::kStageRel;

namespace {

// Flags every third dynamic body of the stack scene.
void flagSome(ref::ContactBodies& b)
{
    for (size_t i = 1; i < b.props.size(); i += 3) b.props[i].flags |= BTG_BODY_CUSTOM_MATERIAL;
}

void expectNearLanes(BtgFloat4 got, BtgFloat4 want, const char* what, size_t i)
{
    const float g[4] = {got.x, got.y, got.z, got.w}, e[4] = {want.x, want.y, want.z, want.w};
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(g[k], e[k], kStageAbs + kStageRel * std::fabs(e[k])) << what << " " << i << " " << k;
}

}  // namespace

TEST(ContactCallbacks, GatherFindsTheFlaggedPairsManifolds)
{
    for (int columns : {4, 40}) {  // 40 x 10: more than the gather's first buffer of 256
        test::StackScene s = test::stackScene(columns, 10, 3u + unsigned(columns));
        if (columns == 40)
            for (BtgBodyProps& p : s.bodies.props) p.flags |= BTG_BODY_CUSTOM_MATERIAL;
        else flagSome(s.bodies);
        DeviceWorld w(test::context());
        const uint pairs = uint(s.manifolds.size()) - 2;  // the last two pair slots past the count
        test::uploadWorld(w, s.bodies, s.manifolds, pairs, {}, 2 * s.manifolds.size());
        const std::vector<GatheredManifold> got = gatherCallbackManifolds(w);
        const std::vector<uint> want =
            ref::gatherCallbackManifolds(ref::oneManifoldPerPair(s.manifolds), pairs, s.manifolds, s.bodies.props);
        ASSERT_GT(want.size(), 0u);
        ASSERT_EQ(got.size(), want.size());
        for (size_t i = 0; i < want.size(); ++i) {
            EXPECT_EQ(got[i].slot, want[i]) << i;
            EXPECT_EQ(got[i].added, -2) << i;  // no persistent state uploaded: every point is the substep's own
            EXPECT_EQ(std::memcmp(&got[i].manifold, &s.manifolds[want[i]], sizeof(BtgManifold)), 0) << i;
        }
    }
}

TEST(ContactCallbacks, ScatterAndMaterialsAsTheReference)
{
    test::StackScene s = test::stackScene(5, 4, 17u);
    flagSome(s.bodies);
    const BtgStepParams params = test::defaultParams(int(s.bodies.props.size()));
    const uint pairs = uint(s.manifolds.size());
    // The host's changes: one manifold's normal tilted and its points lowered.
    std::vector<GatheredManifold> changed = {{2u, s.manifolds[2]}};
    BtgManifold& m = changed[0].manifold;
    for (int k = 0; k < m.numPoints; ++k) {
        m.points[k].distance -= 0.003f;
        m.points[k].nx = 0.0f;
        m.points[k].ny = 0.9950371902f;
        m.points[k].nz = 0.0995037190f;
    }
    std::vector<BtgManifold> expectManifolds = s.manifolds;
    expectManifolds[2] = m;
    // Materials of three manifolds: one with a restitution per point, one as the bodies' own.
    std::vector<BtgContactMaterial> materials(3);
    materials[0].slot = 2;
    materials[0].friction = 0.05f;
    materials[0].restitution = btgMake4(0.9f, 0.1f, 0.9f, 0.5f);
    materials[1].slot = 7;
    materials[1].friction = 2.5f;
    materials[1].restitution = btgMake4(1.0f, 1.0f, 1.0f, 1.0f);
    const BtgManifold& own = s.manifolds[11];
    const BtgBodyProps &pa = s.bodies.props[size_t(own.bodyA)], &pb = s.bodies.props[size_t(own.bodyB)];
    materials[2].slot = 11;
    materials[2].friction = btgCombinedFriction(pa.friction, pb.friction);
    const float r = pa.restitution * pb.restitution;
    materials[2].restitution = btgMake4(r, r, r, r);

    DeviceWorld w(test::context());
    test::uploadWorld(w, s.bodies, s.manifolds, pairs, {}, 2 * s.manifolds.size());
    sendCallbackChanges(w, changed, materials);
    EXPECT_EQ(w.numMaterials, 3);
    std::vector<BtgManifold> gotManifolds = w.manifolds.download(w.ctx, s.manifolds.size());
    for (size_t i = 0; i < s.manifolds.size(); ++i)
        EXPECT_EQ(std::memcmp(&gotManifolds[i], &expectManifolds[i], sizeof(BtgManifold)), 0) << i;

    // The reference: contacts of the changed manifolds, prepared, then the materials.
    ref::BuiltContacts built =
        ref::buildContactsFromRanges(ref::oneManifoldPerPair(expectManifolds), expectManifolds, int(pairs), s.bodies, {}, params);
    ref::prepareContacts(built.contacts, s.bodies, params);
    const std::vector<BtgContact> prepared = built.contacts;
    std::vector<BtgContact> want = prepared;
    ref::applyContactMaterials(want, built.manifoldOf, want.size(), materials, s.bodies.props, s.bodies.invInertiaWorld,
                               s.bodies.linVel0, s.bodies.angVel0, s.bodies.linVel, s.bodies.angVel, params);
    // The device: the same prepared list, then the stage.
    w.contacts.upload(w.ctx, prepared);
    w.contactManifolds.upload(w.ctx, built.manifoldOf);
    std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    counters[kContactCount] = uint(prepared.size());
    w.counters.upload(w.ctx, counters);
    applyContactMaterials(w, params);
    EXPECT_EQ(w.numMaterials, 0);  // used once
    const std::vector<BtgContact> got = w.contacts.download(w.ctx, prepared.size());
    int touched = 0;
    for (size_t i = 0; i < want.size(); ++i) {
        const uint slot = built.manifoldOf[i];
        const bool named = slot == 2 || slot == 7 || slot == 11;
        if (!named || slot == 11) {
            // Untouched, or prepared again with the bodies' own values: the first preparation.
            EXPECT_EQ(std::memcmp(&want[i], &prepared[i], sizeof(BtgContact)), 0) << i;
            EXPECT_EQ(std::memcmp(&got[i], &prepared[i], sizeof(BtgContact)), 0) << i;
            continue;
        }
        ++touched;
        EXPECT_EQ(got[i].friction, want[i].friction) << i;
        EXPECT_NE(want[i].friction, prepared[i].friction) << i;
        expectNearLanes(got[i].normalTarget, want[i].normalTarget, "normalTarget", i);
        expectNearLanes(got[i].pushTarget, want[i].pushTarget, "pushTarget", i);
        expectNearLanes(got[i].normalMass, want[i].normalMass, "normalMass", i);
    }
    EXPECT_EQ(touched, 2);
}
