/* contact_report.h — what the host needs of one solved contact manifold to fill the app's
 * btPersistentManifold (compat/manifold_sync.cpp): its bodies and sub-shape keys and, per point,
 * the world point on B, distance, normal, points in each body's frame, the applied normal and
 * lateral impulses and lateral direction 1 (direction 2 is normal x direction 1, as
 * btgFrictionDir2). Shared by report_contacts.cl and its CPU reference. */
#ifndef BTG_CONTACT_REPORT_H
#define BTG_CONTACT_REPORT_H
#include "prelude.h"
#include "types.h"
#include "math.h"
#include "contact_rows.h"

typedef struct {
    int bodyA;
    int bodyB;
    int numPoints;
    int persistent;                  /* 1: a GJK pair's persistent manifold, whose points are the
                                        whole of stock's (its refresh done on the device) */
    int partIdA;                     /* the manifold's sub-shape keys (BtgManifold's) */
    int indexA;
    int partIdB;
    int indexB;
    BtgFloat4 pointB[BTG_MAX_POINTS];  /* xyz world point on B, m; w: distance, m (m_distance1) */
    BtgFloat4 normal[BTG_MAX_POINTS];  /* xyz world unit normal from B towards A; w: 0 */
    BtgFloat4 localA[BTG_MAX_POINTS];  /* xyz point on A in A's body frame; w: normal impulse, N s */
    BtgFloat4 localB[BTG_MAX_POINTS];  /* xyz point on B in B's body frame; w: lateral impulse 1, N s */
    BtgFloat4 dir1[BTG_MAX_POINTS];    /* xyz lateral friction direction 1; w: lateral impulse 2, N s */
    uint featureId[BTG_MAX_POINTS];    /* BTG_FEATURE_*: the point's identity across steps */
} BtgContactReport;

#ifndef __OPENCL_C_VERSION__
static_assert(sizeof(BtgContactReport) == 32 + 5 * 16 * BTG_MAX_POINTS + 4 * BTG_MAX_POINTS, "BtgContactReport layout");
#endif

/* One solved contact c of manifold m; pos/rot of A and B as the contact was built (before the
 * bodies are integrated). */
static inline BtgContactReport btgContactReportFrom(const BtgContact* c, BtgManifold m, BtgFloat4 posA, BtgFloat4 rotA,
                                                    BtgFloat4 posB, BtgFloat4 rotB)
{
    BtgContactReport r;
    r.bodyA = m.bodyA;
    r.bodyB = m.bodyB;
    r.numPoints = m.numPoints;
    r.persistent = 0;
    r.partIdA = m.partIdA;
    r.indexA = m.indexA;
    r.partIdB = m.partIdB;
    r.indexB = m.indexB;
    BtgMat3 ra = btgQuatToMat3(rotA), rb = btgQuatToMat3(rotB);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        r.pointB[k] = btgZero4();
        r.normal[k] = btgZero4();
        r.localA[k] = btgZero4();
        r.localB[k] = btgZero4();
        r.dir1[k] = btgZero4();
        r.featureId[k] = BTG_FEATURE_UNKNOWN;
        if (k >= m.numPoints) continue;
        BtgManifoldPoint p = m.points[k];
        BtgFloat4 n = btgMake4(p.nx, p.ny, p.nz, 0.0f);
        BtgFloat4 pb = btgMake4(p.px, p.py, p.pz, 0.0f);
        BtgFloat4 pa = pb + n * p.distance;
        r.pointB[k] = btgMake4(p.px, p.py, p.pz, p.distance);
        r.normal[k] = n;
        r.localA[k] = btgMat3TMulVec(ra, pa - btgXyz(posA));
        r.localA[k].w = btgLane(c->normalImpulse, k);
        r.localB[k] = btgMat3TMulVec(rb, pb - btgXyz(posB));
        r.localB[k].w = btgLane(c->friction1Impulse, k);
        r.dir1[k] = btgFrictionDir1(c, k);
        r.dir1[k].w = btgLane(c->friction2Impulse, k);
        r.featureId[k] = p.featureId;
    }
    return r;
}

#endif
