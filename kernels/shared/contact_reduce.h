/* contact_reduce.h — deterministic reduction of candidate contact points to at most
 * BTG_MAX_POINTS. Three passes over the candidates, so a caller may stream them (hull–plane
 * recomputes its vertices rather than buffering them) or loop over a private array (clipping).
 * The choice follows Bullet's intent (keep the deepest point, maximise the area) in the form
 * Jolt's PruneContactPoints uses: deepest, farthest from it, then the largest triangle on each
 * side of that diagonal, which together span a quad of maximal area. Ties go to the earlier
 * candidate, so the result is a pure function of the candidate order. Each candidate carries
 * its feature id into the manifold point it becomes. */
#ifndef BTG_CONTACT_REDUCE_H
#define BTG_CONTACT_REDUCE_H
#include "types.h"

#define BTG_REDUCE_MIN_DIST 1e-4f /* m: candidates closer than this (in the contact plane) are one point */

typedef struct {
    BtgFloat4 normal; /* world unit normal: distances and areas are measured in its plane */
    BtgFloat4 p[4];   /* deepest, farthest from it, largest triangle on the + and - side */
    uint id[4];       /* their feature ids */
    float score[4];
    int has[4];
    float diagonal;   /* m: in-plane distance between p[0] and p[1] */
} BtgReduceState;

static inline BtgFloat4 btgInPlane(BtgFloat4 v, BtgFloat4 n) { return btgXyz(v) - n * btgDot3(v, n); }

static inline void btgReduceBegin(BtgReduceState* s, BtgFloat4 normal)
{
    s->normal = normal;
    for (int k = 0; k < 4; ++k) {
        s->p[k] = btgZero4();
        s->id[k] = BTG_FEATURE_UNKNOWN;
        s->score[k] = 0.0f;
        s->has[k] = 0;
    }
    s->diagonal = 0.0f;
}

/* Pass 0 picks the deepest, pass 1 the farthest from it, pass 2 one point on each side.
 * c: xyz the candidate on B, w its signed distance; id its feature id (carried, never compared). */
static inline void btgReduceVisit(BtgReduceState* s, int pass, BtgFloat4 c, uint id)
{
    if (pass == 0) {
        if (!s->has[0] || c.w < s->p[0].w) {
            s->p[0] = c;
            s->id[0] = id;
            s->has[0] = 1;
        }
    } else if (pass == 1) {
        BtgFloat4 d = btgInPlane(c - s->p[0], s->normal);
        float d2 = btgDot3(d, d);
        if (d2 > BTG_REDUCE_MIN_DIST * BTG_REDUCE_MIN_DIST && (!s->has[1] || d2 > s->score[1])) {
            s->p[1] = c;
            s->id[1] = id;
            s->score[1] = d2;
            s->has[1] = 1;
        }
    } else if (s->has[1]) {
        /* twice the signed triangle area; beyond diagonal * MIN_DIST the point is off the line */
        float a = btgDot3(btgCross3(btgXyz(s->p[1] - s->p[0]), btgXyz(c - s->p[0])), s->normal);
        float minArea = s->diagonal * BTG_REDUCE_MIN_DIST;
        if (a > minArea && (!s->has[2] || a > s->score[2])) {
            s->p[2] = c;
            s->id[2] = id;
            s->score[2] = a;
            s->has[2] = 1;
        }
        if (-a > minArea && (!s->has[3] || -a > s->score[3])) {
            s->p[3] = c;
            s->id[3] = id;
            s->score[3] = -a;
            s->has[3] = 1;
        }
    }
}

static inline void btgReduceEndPass(BtgReduceState* s, int pass)
{
    if (pass == 1 && s->has[1]) s->diagonal = btgSqrt(s->score[1]);
}

/* Writes the chosen points in polygon order (deepest, + side, farthest, - side), each with the
 * reduction's normal. */
static inline void btgReduceWrite(const BtgReduceState* s, BtgManifold* m)
{
    int order[4] = {0, 2, 1, 3};
    m->numPoints = 0;
    for (int k = 0; k < 4; ++k) {
        int j = order[k];
        if (!s->has[j]) continue;
        BtgManifoldPoint p;
        p.px = s->p[j].x;
        p.py = s->p[j].y;
        p.pz = s->p[j].z;
        p.distance = s->p[j].w;
        p.nx = s->normal.x;
        p.ny = s->normal.y;
        p.nz = s->normal.z;
        p.featureId = s->id[j];
        m->points[m->numPoints++] = p;
    }
}

/* The common case: candidates (and their feature ids) in private arrays. */
static inline void btgReduceArray(const BtgFloat4* pts, const uint* ids, int n, BtgFloat4 normal, BtgManifold* m)
{
    BtgReduceState s;
    btgReduceBegin(&s, normal);
    for (int pass = 0; pass < 3; ++pass) {
        for (int i = 0; i < n; ++i) btgReduceVisit(&s, pass, pts[i], ids[i]);
        btgReduceEndPass(&s, pass);
    }
    btgReduceWrite(&s, m);
}

#endif
