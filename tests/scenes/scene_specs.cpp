// scene_specs.cpp — builds the large scenes described in scene_specs.h.
#include "scene_specs.h"

#include "mesh_scenes.h"

#include <algorithm>
#include <cmath>

namespace btgpu::scenes::spec {

namespace {

// The ground: a static box of half extent 400 whose top face is y = 0.
BodySpec ground()
{
    BodySpec g;
    g.half[0] = g.half[1] = g.half[2] = 400;
    g.pos[1] = -400;
    return g;
}

// xorshift32: std::uniform_real_distribution differs between standard libraries, and the
// mixed scene must be the same everywhere.
struct Rng {
    std::uint32_t s;
    float uniform(float lo, float hi)
    {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        return lo + (hi - lo) * float(s >> 8) * (1.0f / 16777216.0f);
    }
};

}  // namespace

int Scene::dynamicCount() const
{
    int n = 0;
    for (const BodySpec& b : bodies) n += b.mass > 0;
    return n;
}

Scene makeStack(int nx, int ny, int nz, ShapeKind shape)
{
    Scene s;
    s.name = std::string(shape == ShapeKind::Box ? "cubes " : "spheres ") + std::to_string(nx) + "x" +
             std::to_string(ny) + "x" + std::to_string(nz);
    s.bodies.reserve(size_t(nx) * ny * nz + 1);
    s.bodies.push_back(ground());
    const float pitch = 2.2f;
    for (int y = 0; y < ny; ++y) {
        float shift = (y & 1) ? 1.0f : 0.0f;  // every other layer shifted by +1 in x and z
        for (int z = 0; z < nz; ++z)
            for (int x = 0; x < nx; ++x) {
                BodySpec b;
                b.shape = shape;
                b.mass = 1;
                b.pos[0] = (x - 0.5f * (nx - 1)) * pitch + shift;
                b.pos[1] = 1.2f + y * pitch;  // bottom layer 0.2 above the ground
                b.pos[2] = (z - 0.5f * (nz - 1)) * pitch + shift;
                s.bodies.push_back(b);
            }
    }
    return s;
}

Scene makeMixed(std::uint32_t seed)
{
    Scene s;
    s.name = "mixed 32x32x32";
    s.bodies.push_back(ground());
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) {
            BodySpec p;
            p.half[0] = p.half[1] = p.half[2] = 25;
            p.pos[0] = (i - 1.5f) * 60;
            p.pos[1] = 25;  // standing on the ground
            p.pos[2] = (k - 1.5f) * 60;
            s.bodies.push_back(p);
        }
    Rng rng{seed ? seed : 1u};
    const int n = 32;
    const float pitch = 6;
    for (int y = 0; y < n; ++y)
        for (int z = 0; z < n; ++z)
            for (int x = 0; x < n; ++x) {
                BodySpec b;
                for (float& h : b.half) h = rng.uniform(0.1f, 2.5f);
                b.mass = 8 * b.half[0] * b.half[1] * b.half[2];  // density 1
                b.pos[0] = (x - 0.5f * (n - 1)) * pitch;
                b.pos[1] = 60 + y * pitch;
                b.pos[2] = (z - 0.5f * (n - 1)) * pitch;
                s.bodies.push_back(b);
            }
    return s;
}

Scene makeLandscape(int count, int quads)
{
    Scene s;
    s.name = "landscape " + std::to_string(count) + " on " + std::to_string(2 * quads * quads) + " triangles";
    const float cell = 200.0f / float(quads), half = 100.0f;
    for (int i = 0; i <= quads; ++i)
        for (int j = 0; j <= quads; ++j) {
            float x = -half + cell * float(i), z = -half + cell * float(j);
            s.meshVertices.insert(s.meshVertices.end(), {x, scenes::landscapeHeight(x, z), z});
        }
    for (int i = 0; i < quads; ++i)
        for (int j = 0; j < quads; ++j) {
            int a = i * (quads + 1) + j, b = a + 1, c = a + quads + 1, d = c + 1;
            s.meshIndices.insert(s.meshIndices.end(), {a, b, d, a, d, c});
        }
    BodySpec ground;
    ground.shape = ShapeKind::Mesh;
    s.bodies.push_back(ground);
    const int side = std::max(1, int(std::ceil(std::sqrt(double(count) / 4.0))));
    const float pitch = std::min(1.6f, 190.0f / float(side));
    int made = 0;
    for (int layer = 0; made < count; ++layer)
        for (int i = 0; i < side && made < count; ++i)
            for (int j = 0; j < side && made < count; ++j, ++made) {
                BodySpec b;
                b.shape = made % 2 ? ShapeKind::Sphere : ShapeKind::Box;
                b.half[0] = b.half[1] = b.half[2] = 0.5f;
                b.radius = 0.5f;
                b.mass = 1;
                b.pos[0] = -0.5f * pitch * float(side) + pitch * float(i);
                b.pos[2] = -0.5f * pitch * float(side) + pitch * float(j);
                b.pos[1] = scenes::landscapeHeight(b.pos[0], b.pos[2]) + 3.0f + 1.6f * float(layer);
                s.bodies.push_back(b);
            }
    return s;
}

bool dimsForCount(long n, int dims[3])
{
    struct Size { long n; int x, y, z; };
    static const Size kSizes[] = {{1000, 10, 10, 10}, {8000, 20, 20, 20}, {32768, 32, 32, 32},
                                  {112500, 50, 45, 50}, {1000000, 100, 100, 100}};
    for (const Size& s : kSizes)
        if (s.n == n) {
            dims[0] = s.x, dims[1] = s.y, dims[2] = s.z;
            return true;
        }
    return false;
}

namespace {

// btMatrix3x3::setEulerZYX(0, yaw, roll)-style rotations of RagdollDemo, as quaternions: about
// y by `y`, then about z by `z` (each demo frame uses one of them).
void setQuat(float* q, float axisY, float axisZ)
{
    const float hy = 0.5f * axisY, hz = 0.5f * axisZ;
    // q = qz * qy (EulerZYX with x = 0: R = Rz Ry)
    const float cy = std::cos(hy), sy = std::sin(hy), cz = std::cos(hz), sz = std::sin(hz);
    q[0] = -sz * sy;
    q[1] = cz * sy;
    q[2] = sz * cy;
    q[3] = cz * cy;
}

JointSpec joint(JointSpec::Kind kind, int a, int b, float yA, float zA, float ax, float ay, float yB, float zB, float bx,
                float by, float l0, float l1, float l2 = 0)
{
    JointSpec j;
    j.kind = kind;
    j.a = a;
    j.b = b;
    j.frameA[0] = ax;
    j.frameA[1] = ay;
    setQuat(j.frameA + 3, yA, zA);
    j.frameB[0] = bx;
    j.frameB[1] = by;
    setQuat(j.frameB + 3, yB, zB);
    j.limit[0] = l0;
    j.limit[1] = l1;
    j.limit[2] = l2;
    return j;
}

}  // namespace

void ragdollLayout(float scale, RagdollPart parts[11], JointSpec joints[10])
{
    const float pi = 3.14159265358979f, half = pi / 2, quarter = pi / 4;
    // Capsule (radius, height) of each part, its centre and its roll about z, as RagdollDemo.
    const RagdollPart unit[11] = {{0.15f, 0.20f, 0, 1.0f, 0},           {0.15f, 0.28f, 0, 1.2f, 0},
                                  {0.10f, 0.05f, 0, 1.6f, 0},           {0.07f, 0.45f, -0.18f, 0.65f, 0},
                                  {0.05f, 0.37f, -0.18f, 0.2f, 0},      {0.07f, 0.45f, 0.18f, 0.65f, 0},
                                  {0.05f, 0.37f, 0.18f, 0.2f, 0},       {0.05f, 0.33f, -0.35f, 1.45f, half},
                                  {0.04f, 0.25f, -0.7f, 1.45f, half},   {0.05f, 0.33f, 0.35f, 1.45f, -half},
                                  {0.04f, 0.25f, 0.7f, 1.45f, -half}};
    for (int i = 0; i < 11; ++i) {
        parts[i] = unit[i];
        parts[i].radius *= scale;
        parts[i].height *= scale;
        parts[i].x *= scale;
        parts[i].y *= scale;
    }
    using K = JointSpec::Kind;
    const float k = scale;
    // Pelvis 0, spine 1, head 2, left upper/lower leg 3/4, right 5/6, left upper/lower arm
    // 7/8, right 9/10: RagdollDemo's frames and limits.
    joints[0] = joint(K::Hinge, 0, 1, half, 0, 0, 0.15f * k, half, 0, 0, -0.15f * k, -quarter, half);
    joints[1] = joint(K::ConeTwist, 1, 2, 0, half, 0, 0.30f * k, 0, half, 0, -0.14f * k, quarter, quarter, half);
    joints[2] = joint(K::ConeTwist, 0, 3, 0, -quarter * 5, -0.18f * k, -0.10f * k, 0, -quarter * 5, 0, 0.225f * k, quarter,
                      quarter, 0);
    joints[3] = joint(K::Hinge, 3, 4, half, 0, 0, -0.225f * k, half, 0, 0, 0.185f * k, 0, half);
    joints[4] = joint(K::ConeTwist, 0, 5, 0, quarter, 0.18f * k, -0.10f * k, 0, quarter, 0, 0.225f * k, quarter, quarter, 0);
    joints[5] = joint(K::Hinge, 5, 6, half, 0, 0, -0.225f * k, half, 0, 0, 0.185f * k, 0, half);
    joints[6] = joint(K::ConeTwist, 1, 7, 0, pi, -0.2f * k, 0.15f * k, 0, half, 0, -0.18f * k, half, half, 0);
    joints[7] = joint(K::Hinge, 7, 8, half, 0, 0, 0.18f * k, half, 0, 0, -0.14f * k, 0, half);
    joints[8] = joint(K::ConeTwist, 1, 9, 0, 0, 0.2f * k, 0.15f * k, 0, half, 0, -0.18f * k, half, half, 0);
    joints[9] = joint(K::Hinge, 9, 10, half, 0, 0, 0.18f * k, half, 0, 0, -0.14f * k, 0, half);
}

Scene makeRagdolls(int count)
{
    Scene s;
    s.name = "ragdolls " + std::to_string(count);
    s.bodies.push_back(ground());
    const int side = int(std::ceil(std::sqrt(double(count))));
    RagdollPart parts[11];
    JointSpec joints[10];
    ragdollLayout(1.0f, parts, joints);
    for (int r = 0; r < count; ++r) {
        const int base = int(s.bodies.size());
        const float ox = 2.0f * float(r % side - side / 2), oz = 2.0f * float(r / side - side / 2);
        for (const RagdollPart& p : parts) {
            BodySpec b;
            b.shape = ShapeKind::Capsule;
            b.radius = p.radius;
            b.half[0] = b.half[2] = p.radius;
            b.half[1] = 0.5f * p.height;
            b.mass = 1;
            b.pos[0] = ox + p.x;
            b.pos[1] = p.y + 0.1f;
            b.pos[2] = oz;
            setQuat(b.rot, 0, p.roll);
            b.friction = 0.5f;
            b.linearDamping = 0.05f;
            b.angularDamping = 0.85f;
            s.bodies.push_back(b);
        }
        for (JointSpec j : joints) {
            j.a += base;
            j.b += base;
            s.joints.push_back(j);
        }
    }
    return s;
}

namespace {
ChildSpec boxChild(float hx, float hy, float hz, float x, float y, float z)
{
    ChildSpec c;
    c.half[0] = hx;
    c.half[1] = hy;
    c.half[2] = hz;
    c.pos[0] = x;
    c.pos[1] = y;
    c.pos[2] = z;
    return c;
}
}  // namespace

CompoundSpec tableSpec()
{
    CompoundSpec t;
    t.children.push_back(boxChild(0.6f, 0.05f, 0.4f, 0, 0.35f, 0));
    for (int i = 0; i < 4; ++i)
        t.children.push_back(boxChild(0.05f, 0.3f, 0.05f, (i & 1) ? 0.5f : -0.5f, 0, (i & 2) ? 0.3f : -0.3f));
    return t;
}

CompoundSpec dumbbellSpec()
{
    CompoundSpec d;
    for (float x : {-0.5f, 0.5f}) {
        ChildSpec ball;
        ball.shape = ShapeKind::Sphere;
        ball.radius = 0.3f;
        ball.pos[0] = x;
        d.children.push_back(ball);
    }
    d.children.push_back(boxChild(0.5f, 0.08f, 0.08f, 0, 0, 0));
    return d;
}

Scene makeCompounds(int count)
{
    Scene s;
    s.name = "compounds " + std::to_string(count);
    s.compounds = {tableSpec(), dumbbellSpec()};
    BodySpec ground;
    ground.half[0] = ground.half[1] = ground.half[2] = 50;
    ground.pos[1] = -50;
    ground.friction = 0.5f;
    s.bodies.push_back(ground);
    const int side = std::max(1, std::min(10, int(std::ceil(std::sqrt(double(count))))));
    for (int i = 0; i < count; ++i) {
        const int layer = i / (side * side), cell = i % (side * side);
        BodySpec b;
        b.shape = ShapeKind::Compound;
        b.compound = i % 2;
        b.mass = 1;
        b.friction = 0.5f;
        b.pos[0] = 2.0f * (float(cell % side) - 0.5f * float(side - 1));
        b.pos[1] = 1.0f + 1.2f * float(layer);
        b.pos[2] = 2.0f * (float(cell / side) - 0.5f * float(side - 1));
        s.bodies.push_back(b);
    }
    return s;
}

}  // namespace btgpu::scenes::spec
