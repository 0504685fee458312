/* concave.h — what the midphase and the triangle kernels do with either concave kind: the walk
 * of one convex–concave pair (the BVH of a mesh, the cells of a heightfield) and the triangle a
 * sub-pair names, in the concave body's frame. */
#ifndef BTG_CONCAVE_H
#define BTG_CONCAVE_H
#include "compound.h"
#include "heightfield.h"
#include "mesh.h"

/* The concave tables every midphase and triangle kernel takes (rows of the shared tables). */
#define BTG_CONCAVE_TABLES                                                                                   \
    BTG_CONST_GLOBAL BtgMesh *meshes, BTG_CONST_GLOBAL BtgBvhNode *nodes, BTG_CONST_GLOBAL int *parts,       \
        BTG_CONST_GLOBAL BtgTriangle *triangles, BTG_CONST_GLOBAL BtgFloat4 *meshVerts,                      \
        BTG_CONST_GLOBAL BtgHeightfield *heightfields, BTG_CONST_GLOBAL float *heights
#define BTG_CONCAVE_TABLE_ARGS meshes, nodes, parts, triangles, meshVerts, heightfields, heights

static inline int btgIsConcave(int type) { return type == BTG_SHAPE_MESH || type == BTG_SHAPE_HEIGHTFIELD; }

/* The midphase of one broadphase pair: 0 unless exactly one side is concave and the other a
 * convex; else the convex's box (btgMidphaseBox with the pair's threshold, none when `persistent`)
 * walked through the
 * mesh's BVH or over the heightfield's cells. The convex may be a compound's leaf, at its own
 * pose. */
static inline uint btgMidphasePair(BtgPair p, int slot, BTG_CONST_GLOBAL BtgFloat4* pos, BTG_CONST_GLOBAL BtgFloat4* rot,
                                   BTG_CONST_GLOBAL BtgBodyProps* props, BTG_CONST_GLOBAL BtgShape* shapes,
                                   BTG_CHILD_TABLE, BTG_CONCAVE_TABLES, BTG_GLOBAL BtgSubPair* out, uint first,
                                   uint capacity, int persistent)
{
    (void)triangles;
    (void)meshVerts;
    BtgShape sa = btgPairSideShape(p, 0, props, shapes, children), sb = btgPairSideShape(p, 1, props, shapes, children);
    int concaveIsA = btgIsConcave(sa.type);
    BtgShape cs = concaveIsA ? sb : sa, ms = concaveIsA ? sa : sb;
    if (!btgIsConcave(ms.type) || btgIsConcave(cs.type) || cs.type == BTG_SHAPE_PLANE) return 0u;
    int c = concaveIsA ? p.b : p.a, mb = concaveIsA ? p.a : p.b;
    int child = concaveIsA ? p.childB : p.childA;
    /* the bullet mode's manifolds persist, as stock's: its box is stock's, grown by no threshold */
    float t = persistent ? 0.0f : (sa.breakingThreshold < sb.breakingThreshold ? sa.breakingThreshold : sb.breakingThreshold);
    BtgFloat4 cp = pos[c], cq = rot[c];
    if (child != BTG_WHOLE_BODY) btgChildWorld(pos[c], rot[c], children[child - 1], &cp, &cq);
    BtgAabb box = btgMidphaseBox(cp, cq, cs, pos[mb], rot[mb], ms, t);
    if (ms.type == BTG_SHAPE_HEIGHTFIELD)
        return btgHeightfieldWalk(heightfields[ms.mesh], heights, box, slot, out, first, capacity);
    BtgMesh m = meshes[ms.mesh];
    return btgMidphaseWalk(m, nodes, parts, btgQuantizeBox(m, box), slot, out, first, capacity);
}

/* The triangle of sub-pair sp of concave shape `concave`, in its body's frame. */
typedef struct {
    BtgFloat4 v[3]; /* m, the concave body's frame */
} BtgTriangleVerts;

static inline BtgTriangleVerts btgConcaveTriangle(BtgShape concave, BtgSubPair sp, BTG_CONCAVE_TABLES)
{
    (void)meshes;
    (void)nodes;
    (void)parts;
    BtgTriangleVerts v;
    if (concave.type == BTG_SHAPE_HEIGHTFIELD)
        btgHeightfieldTriangle(heightfields[concave.mesh], heights, sp.partId >> 1, sp.index, sp.partId & 1, v.v);
    else
        btgTriangleVertices(concave, triangles[sp.triangle], meshVerts, v.v);
    return v;
}

#endif
