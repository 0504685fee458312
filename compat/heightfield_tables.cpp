// heightfield_tables.cpp — btHeightfieldTerrainShape read into the heightfield table: its grid
// parameters (protected in Bullet, read through pointers to member) and the app's heights
// converted as getRawHeightFieldValue converts them (float; double to float; 8- and 16-bit
// values times the height scale). The app's array is hashed every step, so heights it changes
// between steps are read again.
#include "mesh_tables.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include <cmath>
#include <cstring>
#include <typeinfo>

namespace btgpu {

namespace {

struct HeightfieldPeek : btHeightfieldTerrainShape {
    static constexpr btVector3 btHeightfieldTerrainShape::*kAabbMin = &HeightfieldPeek::m_localAabbMin;
    static constexpr btVector3 btHeightfieldTerrainShape::*kAabbMax = &HeightfieldPeek::m_localAabbMax;
    static constexpr btVector3 btHeightfieldTerrainShape::*kOrigin = &HeightfieldPeek::m_localOrigin;
    static constexpr int btHeightfieldTerrainShape::*kWidth = &HeightfieldPeek::m_heightStickWidth;
    static constexpr int btHeightfieldTerrainShape::*kLength = &HeightfieldPeek::m_heightStickLength;
    static constexpr btScalar btHeightfieldTerrainShape::*kWidthM = &HeightfieldPeek::m_width;
    static constexpr btScalar btHeightfieldTerrainShape::*kLengthM = &HeightfieldPeek::m_length;
    static constexpr btScalar btHeightfieldTerrainShape::*kScale = &HeightfieldPeek::m_heightScale;
    static constexpr const void* btHeightfieldTerrainShape::*kData = &HeightfieldPeek::m_heightfieldDataUnknown;
    static constexpr PHY_ScalarType btHeightfieldTerrainShape::*kType = &HeightfieldPeek::m_heightDataType;
    static constexpr bool btHeightfieldTerrainShape::*kFlipQuad = &HeightfieldPeek::m_flipQuadEdges;
    static constexpr bool btHeightfieldTerrainShape::*kDiamond = &HeightfieldPeek::m_useDiamondSubdivision;
    static constexpr bool btHeightfieldTerrainShape::*kZigzag = &HeightfieldPeek::m_useZigzagSubdivision;
    static constexpr bool btHeightfieldTerrainShape::*kFlipWinding = &HeightfieldPeek::m_flipTriangleWinding;
    static constexpr int btHeightfieldTerrainShape::*kUpAxis = &HeightfieldPeek::m_upAxis;
};
using P = HeightfieldPeek;

size_t heightBytes(PHY_ScalarType type)
{
    switch (type) {
        case PHY_FLOAT: return sizeof(float);
        case PHY_DOUBLE: return sizeof(double);
        case PHY_SHORT: return sizeof(short);
        case PHY_UCHAR: return sizeof(unsigned char);
        default: return 0;
    }
}

// getRawHeightFieldValue, for the types it knows.
float rawHeight(const btHeightfieldTerrainShape* h, int i)
{
    const void* data = h->*P::kData;
    switch (h->*P::kType) {
        case PHY_FLOAT: return static_cast<const float*>(data)[i];
        case PHY_DOUBLE: return btScalar(static_cast<const double*>(data)[i]);
        case PHY_UCHAR: return static_cast<const unsigned char*>(data)[i] * (h->*P::kScale);
        case PHY_SHORT: return static_cast<const short*>(data)[i] * (h->*P::kScale);
        default: return 0.0f;
    }
}

BtgFloat4 f4(const btVector3& v) { return btgMake4(v.x(), v.y(), v.z(), 0.0f); }

}  // namespace

const btHeightfieldTerrainShape* heightfieldOf(const btCollisionShape* shape)
{
    if (shape->getShapeType() != TERRAIN_SHAPE_PROXYTYPE || typeid(*shape) != typeid(btHeightfieldTerrainShape))
        return nullptr;
    return static_cast<const btHeightfieldTerrainShape*>(shape);
}

std::uint64_t heightfieldFingerprint(const btHeightfieldTerrainShape* h)
{
    std::uint64_t x = 0x9e3779b97f4a7c15ull;
    auto mix = [&](const void* p, size_t n) { x = (x ^ hashBytes(p, n)) * 0x100000001b3ull; };
    const int width = h->*P::kWidth, length = h->*P::kLength;
    int ints[6] = {width, length, h->*P::kUpAxis, int(h->*P::kType),
                   (h->*P::kFlipQuad ? 1 : 0) | (h->*P::kDiamond ? 2 : 0) | (h->*P::kZigzag ? 4 : 0) |
                       (h->*P::kFlipWinding ? 8 : 0),
                   0};
    mix(ints, sizeof(ints));
    float floats[3] = {h->*P::kScale, h->*P::kWidthM, h->*P::kLengthM};
    mix(floats, sizeof(floats));
    const void* data = h->*P::kData;
    mix(&data, sizeof(data));
    const size_t bytes = heightBytes(h->*P::kType);
    if (data && width > 0 && length > 0 && bytes) mix(data, size_t(width) * size_t(length) * bytes);
    return x;
}

std::string badHeightfieldInput(const btHeightfieldTerrainShape* h)
{
    const btVector3& s = h->getLocalScaling();
    if (!std::isfinite(s.x()) || !std::isfinite(s.y()) || !std::isfinite(s.z())) return "non-finite heightfield scaling";
    if (s.x() == 0.0f || s.y() == 0.0f || s.z() == 0.0f) return "zero heightfield scaling";
    if (!heightBytes(h->*P::kType) || !(h->*P::kData) || h->*P::kWidth < 2 || h->*P::kLength < 2) return "";
    const int n = (h->*P::kWidth) * (h->*P::kLength);
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(rawHeight(h, i))) return "non-finite height " + std::to_string(i);
    return "";
}

int MeshTables::addHeightfield(const btHeightfieldTerrainShape* h, std::string* whyNot)
{
    if (!heightBytes(h->*P::kType)) {
        *whyNot = "heightfield heights neither float, double, short nor unsigned char";
        return -1;
    }
    if (!(h->*P::kData) || h->*P::kWidth < 2 || h->*P::kLength < 2) {
        *whyNot = "heightfield without data or smaller than 2 x 2";
        return -1;
    }
    const int up = h->*P::kUpAxis;
    if (up < 0 || up > 2) {
        *whyNot = "heightfield up axis not 0, 1 or 2";
        return -1;
    }
    BtgHeightfield d{};
    d.localAabbMin = f4(h->*P::kAabbMin);
    d.localAabbMax = f4(h->*P::kAabbMax);
    d.localOrigin = f4(h->*P::kOrigin);
    d.scaling = f4(h->getLocalScaling());
    d.width = h->*P::kWidth;
    d.length = h->*P::kLength;
    d.upAxis = up;
    d.flags = (h->*P::kFlipQuad ? BTG_HF_FLIP_QUAD_EDGES : 0) | (h->*P::kDiamond ? BTG_HF_DIAMOND : 0) |
              (h->*P::kZigzag ? BTG_HF_ZIGZAG : 0) | (h->*P::kFlipWinding ? BTG_HF_FLIP_WINDING : 0);
    // As getVertex: -m_width / 2 (an exact halving).
    d.halfWidth = (h->*P::kWidthM) / 2.0f;
    d.halfLength = (h->*P::kLengthM) / 2.0f;
    d.firstHeight = int(heights.size());
    const int n = d.width * d.length;
    for (int i = 0; i < n; ++i) heights.push_back(rawHeight(h, i));
    heightfields.push_back(d);
    return int(heightfields.size()) - 1;
}

}  // namespace btgpu
