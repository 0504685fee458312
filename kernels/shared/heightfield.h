/* heightfield.h — btHeightfieldTerrainShape on the device: the grid's parameters and its
 * heights (the app's array read as Bullet's getRawHeightFieldValue reads it), the midphase walk
 * over the cells under a box exactly as btHeightfieldTerrainShape::processAllTriangles does
 * (quantize with clamp, one cell of slack, each triangle's up-range test), and each triangle
 * formed on the fly from its cell (no triangle is stored): up axis 0/1/2, scaling, flipped
 * winding, flipped quad edges, diamond and zigzag subdivision. Shared by kernels/midphase.cl,
 * kernels/narrowphase_mesh.cl and their references. */
#ifndef BTG_HEIGHTFIELD_H
#define BTG_HEIGHTFIELD_H
#include "mesh.h"

#define BTG_HF_FLIP_QUAD_EDGES 1
#define BTG_HF_DIAMOND 2
#define BTG_HF_ZIGZAG 4
#define BTG_HF_FLIP_WINDING 8

typedef struct {
    BtgFloat4 localAabbMin; /* Bullet's m_localAabbMin (unscaled grid units); w 0 */
    BtgFloat4 localAabbMax; /* m_localAabbMax */
    BtgFloat4 localOrigin;  /* m_localOrigin */
    BtgFloat4 scaling;      /* m_localScaling */
    int width;              /* m_heightStickWidth: grid points along the first horizontal axis */
    int length;             /* m_heightStickLength */
    int upAxis;             /* m_upAxis */
    int flags;              /* BTG_HF_* */
    float halfWidth;        /* m_width / 2 */
    float halfLength;       /* m_length / 2 */
    int firstHeight;        /* row in the height table (float, y * width + x) */
    int pad0;
} BtgHeightfield;

static inline float btgAxis(BtgFloat4 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

/* btHeightfieldTerrainShape::getVertex. */
static inline BtgFloat4 btgHeightfieldVertex(BtgHeightfield h, BTG_CONST_GLOBAL float* heights, int x, int y)
{
    float height = heights[h.firstHeight + y * h.width + x];
    float a = -h.halfWidth + (float)x, b = -h.halfLength + (float)y;
    BtgFloat4 v;
    if (h.upAxis == 0) v = btgMake4(height - h.localOrigin.x, a, b, 0.0f);
    else if (h.upAxis == 1) v = btgMake4(a, height - h.localOrigin.y, b, 0.0f);
    else v = btgMake4(a, b, height - h.localOrigin.z, 0.0f);
    return v * btgXyz(h.scaling);
}

/* Quad (x, j) is split along (x, j)-(x+1, j+1) in Bullet's first branch. */
static inline int btgHeightfieldFirstBranch(BtgHeightfield h, int x, int j)
{
    return (h.flags & BTG_HF_FLIP_QUAD_EDGES) || ((h.flags & BTG_HF_DIAMOND) && !((j + x) & 1)) ||
           ((h.flags & BTG_HF_ZIGZAG) && !(j & 1));
}

/* Triangle t (0, 1) of quad (x, j), its vertices in the slots processAllTriangles gives them. */
static inline void btgHeightfieldTriangle(BtgHeightfield h, BTG_CONST_GLOBAL float* heights, int x, int j, int t,
                                          BtgFloat4* v)
{
    const int flip = (h.flags & BTG_HF_FLIP_WINDING) != 0;
    const int i0 = flip ? 2 : 0, i2 = flip ? 0 : 2;
    BtgFloat4 r0, r1, r2; /* the three roles, as Bullet fills indices[0], [1], [2] */
    if (btgHeightfieldFirstBranch(h, x, j)) {
        r0 = btgHeightfieldVertex(h, heights, x, j);
        r1 = btgHeightfieldVertex(h, heights, x + 1 - (t == 0), j + 1);
        r2 = t == 0 ? btgHeightfieldVertex(h, heights, x + 1, j + 1) : btgHeightfieldVertex(h, heights, x + 1, j);
    } else {
        r0 = t == 0 ? btgHeightfieldVertex(h, heights, x, j) : btgHeightfieldVertex(h, heights, x + 1, j);
        r1 = btgHeightfieldVertex(h, heights, x, j + 1);
        r2 = t == 0 ? btgHeightfieldVertex(h, heights, x + 1, j) : btgHeightfieldVertex(h, heights, x + 1, j + 1);
    }
    v[i0] = r0;
    v[1] = r1;
    v[i2] = r2;
}

/* getQuantized. */
static inline int btgHeightfieldQuantize(float x) { return x < 0.0f ? (int)(x - 0.5f) : (int)(x + 0.5f); }

/* The walk of processAllTriangles over the cells under `box` (the body frame, scaled). Counts
 * the triangles whose up-range meets the box's; with `out`, writes sub-pairs (part id 2x + t,
 * index j, as Bullet numbers them) from out[first] on, never past out[capacity - 1]. */
static inline uint btgHeightfieldWalk(BtgHeightfield h, BTG_CONST_GLOBAL float* heights, BtgAabb box, int pairSlot,
                                      BTG_GLOBAL BtgSubPair* out, uint first, uint capacity)
{
    BtgFloat4 inv = btgMake4(1.0f / h.scaling.x, 1.0f / h.scaling.y, 1.0f / h.scaling.z, 0.0f);
    BtgFloat4 lo = box.lo * inv + h.localOrigin, hi = box.hi * inv + h.localOrigin;
    int qlo[3], qhi[3];
    for (int a = 0; a < 3; ++a) {
        float mn = btgAxis(h.localAabbMin, a), mx = btgAxis(h.localAabbMax, a);
        float l = btgAxis(lo, a), u = btgAxis(hi, a);
        l = l < mn ? mn : l;
        l = l > mx ? mx : l;
        u = u < mn ? mn : u;
        u = u > mx ? mx : u;
        qlo[a] = btgHeightfieldQuantize(l) - 1;
        qhi[a] = btgHeightfieldQuantize(u) + 1;
    }
    const int ax = h.upAxis == 0 ? 1 : 0, aj = h.upAxis == 2 ? 1 : 2;
    int startX = qlo[ax] > 0 ? qlo[ax] : 0, endX = qhi[ax] < h.width - 1 ? qhi[ax] : h.width - 1;
    int startJ = qlo[aj] > 0 ? qlo[aj] : 0, endJ = qhi[aj] < h.length - 1 ? qhi[aj] : h.length - 1;
    const float upLo = btgAxis(box.lo, h.upAxis), upHi = btgAxis(box.hi, h.upAxis);
    uint found = 0;
    for (int j = startJ; j < endJ; ++j)
        for (int x = startX; x < endX; ++x) {
            BtgFloat4 v[3];
            float mn = 0.0f, mx = 0.0f;
            for (int t = 0; t < 2; ++t) {
                btgHeightfieldTriangle(h, heights, x, j, t, v);
                /* the second triangle's range is the quad's (Bullet widens the first's) */
                for (int k = 0; k < 3; ++k) {
                    float c = btgAxis(v[k], h.upAxis);
                    mn = (t == 0 && k == 0) || c < mn ? c : mn;
                    mx = (t == 0 && k == 0) || c > mx ? c : mx;
                }
                if (mn > upHi || mx < upLo) continue;
                if (out && first + found < capacity) {
                    BtgSubPair s;
                    s.pair = pairSlot;
                    s.partId = 2 * x + t;
                    s.index = j;
                    s.triangle = j * 2 * (h.width - 1) + 2 * x + t; /* a number for the feature ids only */
                    out[first + found] = s;
                }
                ++found;
            }
        }
    return found;
}

#ifndef __OPENCL_C_VERSION__
static_assert(sizeof(BtgHeightfield) == 96, "BtgHeightfield layout");
#endif

#endif
