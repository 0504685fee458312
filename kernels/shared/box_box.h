/* box_box.h — two btBoxShapes as stock collides them (btBoxBoxCollisionAlgorithm): the points
 * btBoxBoxDetector (dBoxBox2) reports — none while any of the 15 axes separates the boxes, else
 * the deepest axis (edge axes preferred only when 5% deeper), one point for two edges, or the
 * incident face clipped to the reference face, penetrating points only, culled to 4 around the
 * deepest — each added into the pair's persistent manifold, which is then refreshed. So, as on
 * stock, a new contact starts only once the boxes overlap, and a point kept from earlier steps
 * goes on while within the breaking threshold (persistent_manifold.h). */
#ifndef BTG_BOX_BOX_H
#define BTG_BOX_BOX_H
#include "persistent_manifold.h"

#define BTG_BOX_BOX_PI 3.14159265f /* dBoxBox2's M__PI */

/* What the detector hands addContactPoint: one normal (from B towards A), up to 4 points on B's
 * surface and their distances (<= 0), in the detector's order. */
typedef struct {
    BtgFloat4 normal;
    BtgFloat4 pointB[BTG_MAX_POINTS];
    float distance[BTG_MAX_POINTS];
    int count;
    int pad0, pad1, pad2;
} BtgBoxBoxPoints;

/* Column j of a rotation: the body's axis j in world. */
static inline BtgFloat4 btgMat3Column(BtgMat3 m, int j)
{
    if (j == 0) return btgMake4(m.r0.x, m.r1.x, m.r2.x, 0.0f);
    if (j == 1) return btgMake4(m.r0.y, m.r1.y, m.r2.y, 0.0f);
    return btgMake4(m.r0.z, m.r1.z, m.r2.z, 0.0f);
}

/* intersectRectQuad2: the quad q (4 points, 2D) clipped to the rectangle |x| < h0, |y| < h1,
 * one side at a time (-x, +x, -y, +y); at most 8 points, returned in out. */
static inline int btgClipQuadToRect(float h0, float h1, const float* q, float* out)
{
    float bufA[16], bufB[16];
    for (int i = 0; i < 8; ++i) bufA[i] = q[i];
    float* in = bufA;
    float* res = bufB;
    int nq = 4, nr = 0;
    for (int dir = 0; dir <= 1; ++dir) {
        const float h = dir == 0 ? h0 : h1;
        for (int sign = -1; sign <= 1; sign += 2) {
            nr = 0;
            for (int i = 0; i < nq; ++i) {
                const float* cur = in + 2 * i;
                const float* next = in + 2 * ((i + 1) % nq);
                const int curIn = (float)sign * cur[dir] < h, nextIn = (float)sign * next[dir] < h;
                if (curIn) {
                    res[2 * nr] = cur[0];
                    res[2 * nr + 1] = cur[1];
                    if (++nr == 8) goto done;
                }
                if (curIn ^ nextIn) {
                    res[2 * nr + 1 - dir] =
                        cur[1 - dir] + (next[1 - dir] - cur[1 - dir]) / (next[dir] - cur[dir]) * ((float)sign * h - cur[dir]);
                    res[2 * nr + dir] = (float)sign * h;
                    if (++nr == 8) goto done;
                }
            }
            {
                float* t = in;
                in = res;
                res = t;
                nq = nr;
            }
        }
    }
    res = in; /* the last side's output */
done:
    for (int i = 0; i < 2 * nr; ++i) out[i] = res[i];
    return nr;
}

/* cullPoints2: m of the n points p (2D), the first i0, the others nearest the angles i0's
 * angle + k 2 pi / m around the polygon's centroid. */
static inline void btgCullPoints(int n, const float* p, int m, int i0, int* iret)
{
    float cx, cy;
    if (n == 1) {
        cx = p[0];
        cy = p[1];
    } else if (n == 2) {
        cx = 0.5f * (p[0] + p[2]);
        cy = 0.5f * (p[1] + p[3]);
    } else {
        float a = 0.0f, q;
        cx = 0.0f;
        cy = 0.0f;
        for (int i = 0; i < n - 1; ++i) {
            q = p[i * 2] * p[i * 2 + 3] - p[i * 2 + 2] * p[i * 2 + 1];
            a += q;
            cx += q * (p[i * 2] + p[i * 2 + 2]);
            cy += q * (p[i * 2 + 1] + p[i * 2 + 3]);
        }
        q = p[n * 2 - 2] * p[1] - p[0] * p[n * 2 - 1];
        a = btgAbs(a + q) > 1.1920929e-7f ? 1.0f / (3.0f * (a + q)) : 1e30f;
        cx = a * (cx + q * (p[n * 2 - 2] + p[0]));
        cy = a * (cy + q * (p[n * 2 - 1] + p[1]));
    }
    float angle[8];
    int avail[8];
    for (int i = 0; i < n; ++i) {
        angle[i] = btgAtan2(p[i * 2 + 1] - cy, p[i * 2] - cx);
        avail[i] = 1;
    }
    avail[i0] = 0;
    iret[0] = i0;
    for (int j = 1; j < m; ++j) {
        float a = (float)j * (2.0f * BTG_BOX_BOX_PI / (float)m) + angle[i0];
        if (a > BTG_BOX_BOX_PI) a -= 2.0f * BTG_BOX_BOX_PI;
        float best = 1e9f;
        iret[j] = i0;
        for (int i = 0; i < n; ++i) {
            if (!avail[i]) continue;
            float diff = btgAbs(angle[i] - a);
            if (diff > BTG_BOX_BOX_PI) diff = 2.0f * BTG_BOX_BOX_PI - diff;
            if (diff < best) {
                best = diff;
                iret[j] = i;
            }
        }
        avail[iret[j]] = 0;
    }
}

/* dBoxBox2 for a = box 1 and b = box 2 (half extents with margin: BtgShape.param). */
static inline BtgBoxBoxPoints btgBoxBoxPoints(BtgCollider a, BtgCollider b)
{
    BtgBoxBoxPoints out;
    out.count = 0;
    out.normal = btgZero4();
    out.pad0 = out.pad1 = out.pad2 = 0;
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        out.pointB[k] = btgZero4();
        out.distance[k] = 0.0f;
    }
    BtgFloat4 ax[3], bx[3];
    for (int j = 0; j < 3; ++j) {
        ax[j] = btgMat3Column(a.pose.rot, j);
        bx[j] = btgMat3Column(b.pose.rot, j);
    }
    const float A[3] = {a.shape.param.x, a.shape.param.y, a.shape.param.z};
    const float B[3] = {b.shape.param.x, b.shape.param.y, b.shape.param.z};
    const BtgFloat4 p = btgXyz(b.pose.pos) - btgXyz(a.pose.pos);
    float pp[3], R[3][3], Q[3][3];
    for (int i = 0; i < 3; ++i) {
        pp[i] = btgDot3(ax[i], p);
        for (int j = 0; j < 3; ++j) {
            R[i][j] = btgDot3(ax[i], bx[j]);
            Q[i][j] = btgAbs(R[i][j]);
        }
    }
    /* The face axes: A's (codes 1-3), then B's (4-6); on each, the centres' distance e1 against
     * the two boxes' radii e2. */
    float s = -1e30f;
    int invert = 0, code = 0;
    BtgFloat4 normal = btgZero4();
    for (int k = 0; k < 6; ++k) {
        const int i = k % 3;
        const float e1 = k < 3 ? pp[i] : btgDot3(bx[i], p);
        const float e2 = k < 3 ? A[i] + B[0] * Q[i][0] + B[1] * Q[i][1] + B[2] * Q[i][2]
                               : A[0] * Q[0][i] + A[1] * Q[1][i] + A[2] * Q[2][i] + B[i];
        const float s2 = btgAbs(e1) - e2;
        if (s2 > 0.0f) return out;
        if (s2 > s) {
            s = s2;
            normal = k < 3 ? ax[i] : bx[i];
            invert = e1 < 0.0f;
            code = 1 + k;
        }
    }
    BtgFloat4 normalC = btgZero4(); /* the winning edge axis, in A's frame */
    /* The nine edge axes ax[i] x bx[j] (codes 7 + 3i + j), radii on slightly padded Q so that
     * near-parallel edges do not win on rounding; taken only when 5% deeper than the best. */
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Q[i][j] += 1.0e-5f;
    for (int i = 0; i < 3; ++i) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            /* ax[i] x bx[j] in A's frame: components i1, i2 are -/+ R[i2][j], R[i1][j] */
            float n[3];
            n[i] = 0.0f;
            n[i1] = -R[i2][j];
            n[i2] = R[i1][j];
            const float e1 = pp[i1] * n[i1] + pp[i2] * n[i2];
            /* the radii: A's along its other two axes (lower index first), B's likewise */
            const int lo = i1 < i2 ? i1 : i2, hi = i1 < i2 ? i2 : i1;
            const int blo = j1 < j2 ? j1 : j2, bhi = j1 < j2 ? j2 : j1;
            const float e2 = A[lo] * Q[3 - i - lo][j] + A[hi] * Q[3 - i - hi][j] + B[blo] * Q[i][3 - j - blo] +
                             B[bhi] * Q[i][3 - j - bhi];
            float s2 = btgAbs(e1) - e2;
            if (s2 > 1.1920929e-7f) return out;
            const float l = btgSqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (l > 1.1920929e-7f) {
                s2 /= l;
                if (s2 * 1.05f > s) {
                    s = s2;
                    normalC = btgMake4(n[0] / l, n[1] / l, n[2] / l, 0.0f);
                    invert = e1 < 0.0f;
                    code = 7 + 3 * i + j;
                }
            }
        }
    }
    if (!code) return out;
    if (code > 6) normal = ax[0] * normalC.x + ax[1] * normalC.y + ax[2] * normalC.z;
    if (invert) normal = btgZero4() - normal;
    normal = btgXyz(normal);
    const float depth = -s;
    out.normal = btgZero4() - normal; /* addContactPoint's normalOnB: from B towards A */
    if (code > 6) {
        /* two edges: the point on B's edge closest to A's */
        BtgFloat4 pa = btgXyz(a.pose.pos), pb = btgXyz(b.pose.pos);
        for (int j = 0; j < 3; ++j) {
            pa = pa + ax[j] * ((btgDot3(normal, ax[j]) > 0.0f ? 1.0f : -1.0f) * A[j]);
            pb = pb + bx[j] * ((btgDot3(normal, bx[j]) > 0.0f ? -1.0f : 1.0f) * B[j]);
        }
        const BtgFloat4 ua = ax[(code - 7) / 3], ub = bx[(code - 7) % 3];
        const BtgFloat4 d = pb - pa;
        const float uaub = btgDot3(ua, ub), q1 = btgDot3(ua, d), q2 = -btgDot3(ub, d);
        float den = 1.0f - uaub * uaub, beta = 0.0f;
        if (den > 0.0001f) beta = (uaub * q1 + q2) * (1.0f / den);
        out.pointB[0] = pb + ub * beta;
        out.distance[0] = -depth;
        out.count = 1;
        return out;
    }
    /* A face: the reference box's face along the normal, the other box's most opposed face
     * clipped to it in the reference face's 2D frame. */
    const int refA = code <= 3;
    BtgFloat4 ra[3], rb[3];
    float Sa[3], Sb[3];
    for (int j = 0; j < 3; ++j) {
        ra[j] = refA ? ax[j] : bx[j];
        rb[j] = refA ? bx[j] : ax[j];
        Sa[j] = refA ? A[j] : B[j];
        Sb[j] = refA ? B[j] : A[j];
    }
    const BtgFloat4 pa = refA ? btgXyz(a.pose.pos) : btgXyz(b.pose.pos);
    const BtgFloat4 pb = refA ? btgXyz(b.pose.pos) : btgXyz(a.pose.pos);
    const BtgFloat4 normal2 = refA ? normal : btgZero4() - normal;
    float nr[3], anr[3];
    for (int j = 0; j < 3; ++j) {
        nr[j] = btgDot3(rb[j], normal2);
        anr[j] = btgAbs(nr[j]);
    }
    int lanr, a1, a2;
    if (anr[1] > anr[0]) {
        if (anr[1] > anr[2]) {
            a1 = 0; lanr = 1; a2 = 2;
        } else {
            a1 = 0; a2 = 1; lanr = 2;
        }
    } else {
        if (anr[0] > anr[2]) {
            lanr = 0; a1 = 1; a2 = 2;
        } else {
            a1 = 0; a2 = 1; lanr = 2;
        }
    }
    const BtgFloat4 center = nr[lanr] < 0.0f ? pb - pa + rb[lanr] * Sb[lanr] : pb - pa - rb[lanr] * Sb[lanr];
    const int codeN = refA ? code - 1 : code - 4;
    const int code1 = codeN == 0 ? 1 : 0, code2 = codeN == 2 ? 1 : 2;
    const float c1 = btgDot3(center, ra[code1]), c2 = btgDot3(center, ra[code2]);
    float m11 = btgDot3(ra[code1], rb[a1]), m12 = btgDot3(ra[code1], rb[a2]);
    float m21 = btgDot3(ra[code2], rb[a1]), m22 = btgDot3(ra[code2], rb[a2]);
    float quad[8];
    {
        const float k1 = m11 * Sb[a1], k2 = m21 * Sb[a1], k3 = m12 * Sb[a2], k4 = m22 * Sb[a2];
        quad[0] = c1 - k1 - k3;
        quad[1] = c2 - k2 - k4;
        quad[2] = c1 - k1 + k3;
        quad[3] = c2 - k2 + k4;
        quad[4] = c1 + k1 + k3;
        quad[5] = c2 + k2 + k4;
        quad[6] = c1 + k1 - k3;
        quad[7] = c2 + k2 - k4;
    }
    float ret[16];
    const int n = btgClipQuadToRect(Sa[code1], Sa[code2], quad, ret);
    if (n < 1) return out;
    const float det1 = 1.0f / (m11 * m22 - m12 * m21);
    m11 *= det1;
    m12 *= det1;
    m21 *= det1;
    m22 *= det1;
    BtgFloat4 point[8];
    float dep[8];
    int cnum = 0;
    for (int j = 0; j < n; ++j) {
        const float k1 = m22 * (ret[j * 2] - c1) - m12 * (ret[j * 2 + 1] - c2);
        const float k2 = -m21 * (ret[j * 2] - c1) + m11 * (ret[j * 2 + 1] - c2);
        point[cnum] = center + rb[a1] * k1 + rb[a2] * k2;
        dep[cnum] = Sa[codeN] - btgDot3(normal2, point[cnum]);
        if (dep[cnum] >= 0.0f) {
            ret[cnum * 2] = ret[j * 2];
            ret[cnum * 2 + 1] = ret[j * 2 + 1];
            ++cnum;
        }
    }
    if (cnum < 1) return out;
    int pick[BTG_MAX_POINTS];
    int count = cnum;
    if (cnum <= BTG_MAX_POINTS) {
        for (int j = 0; j < cnum; ++j) pick[j] = j;
    } else {
        int deepest = 0;
        for (int i = 1; i < cnum; ++i)
            if (dep[i] > dep[deepest]) deepest = i;
        btgCullPoints(cnum, ret, BTG_MAX_POINTS, deepest, pick);
        count = BTG_MAX_POINTS;
    }
    for (int j = 0; j < count; ++j) {
        const int k = pick[j];
        /* on B's surface: the incident face's point when B is incident, else A's point moved
         * onto B's reference face */
        out.pointB[j] = refA ? point[k] + pa : point[k] + pa - normal * dep[k];
        out.distance[j] = -dep[k];
    }
    out.count = count;
    return out;
}

/* One step of a box pair's persistent manifold (btBoxBoxCollisionAlgorithm::processCollision:
 * the detector's points added one by one, then refreshContactPoints). */
static inline BtgPersistentManifold btgBoxBoxStep(BtgPersistentManifold prev, BtgCollider a, BtgCollider b,
                                                  float threshold, float* dist)
{
    BtgPersistentManifold m = prev;
    m.added = -1;
    m.addedMask = 0u;
    btgPersistentBegin(&m, dist);
    const BtgBoxBoxPoints pts = btgBoxBoxPoints(a, b);
    for (int k = 0; k < pts.count; ++k)
        btgPersistentAdd(&m, dist, &prev, pts.normal, pts.pointB[k], pts.distance[k], a.pose, b.pose, threshold,
                         BTG_FEATURE_UNKNOWN);
    if (pts.count > 1) m.added = -2; /* several added this step */
    btgPersistentRefresh(&m, dist, a.pose, b.pose, threshold);
    return m;
}

/* The same with the narrowphase programs' step arguments (BTG_PERSISTENT_STEP). */
static inline BtgPersistentManifold btgBoxBoxPairStep(BtgPersistentManifold prev, BtgCollider a, BtgCollider b,
                                                      BTG_SHAPE_TABLES, float threshold, float* dist)
{
    return btgBoxBoxStep(prev, a, b, threshold, dist);
}

/* The routine the pair-kind table names for two boxes: a new pair's first step. */
static inline BtgManifold btgCollideBoxBox(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    float dist[BTG_MAX_POINTS];
    BtgPersistentManifold pm = btgBoxBoxStep(btgEmptyPersistent(a.body, b.body, 0), a, b, threshold, dist);
    return btgManifoldFromPersistent(pm, dist, b.pose);
}

#endif
