// accuracy_scenes.cpp — builders of btgpu_accuracy's reference scenes: copies on a grid, one
// shared ground where the scene needs one. Every dynamic body has DISABLE_DEACTIVATION: the
// tool times the solver, and a copy falling asleep would make stock look cheaper per step.
#include "scenes/accuracy_scenes.h"

#include <algorithm>
#include <cmath>

namespace btgpu::scenes {

namespace {

int gridSide(int copies)
{
    return std::max(1, int(std::ceil(std::sqrt(double(copies)))));
}

// Centre of copy i (y = 0), the grid centred on the origin; spacing wider than kCopySpacing
// for copies that are wider themselves.
btVector3 cell(int i, int copies, double spacing = kCopySpacing)
{
    const int side = gridSide(copies);
    const double x = (i % side - 0.5 * (side - 1)) * spacing;
    const double z = (i / side - 0.5 * (side - 1)) * spacing;
    return btVector3(btScalar(x), 0, btScalar(z));
}

// One ground box under every copy, top face at y = 0.
void addSharedGround(Scene& scene, int copies, const Material& material, double spacing = kCopySpacing)
{
    const btScalar half = btScalar(0.5 * gridSide(copies) * spacing + 20);
    scene.addBody(scene.boxShape(btVector3(half, half, half)), 0, btVector3(0, -half, 0), material);
}

btRigidBody* addAwake(Scene& scene, btCollisionShape* shape, btScalar mass, const btTransform& t, const Material& m)
{
    btRigidBody* body = scene.addBody(shape, mass, t, m);
    body->setActivationState(DISABLE_DEACTIVATION);
    return body;
}

btRigidBody* addAwake(Scene& scene, btCollisionShape* shape, btScalar mass, const btVector3& origin,
                      const Material& m = Material())
{
    btTransform t;
    t.setIdentity();
    t.setOrigin(origin);
    return addAwake(scene, shape, mass, t, m);
}

AccuracyScene start(WorldKind kind, const Config& config, const char* name, int copies, int perCopy, bool ground)
{
    AccuracyScene a;
    a.scene = std::make_unique<Scene>(kind, config, name);
    a.copies = copies;
    a.bodiesPerCopy = perCopy;
    a.firstBody = ground ? 1 : 0;
    return a;
}

}  // namespace

AccuracyScene accuracyFreeFall(WorldKind kind, const Config& config, int copies)
{
    AccuracyScene a = start(kind, config, "free_fall", copies, 1, false);
    btBoxShape* box = a.scene->boxShape(btVector3(.5, .5, .5));
    for (int i = 0; i < copies; ++i) addAwake(*a.scene, box, 1, cell(i, copies) + btVector3(0, 30, 0));
    return a;
}

AccuracyScene accuracyProjectile(WorldKind kind, const Config& config, int copies)
{
    AccuracyScene a = start(kind, config, "projectile", copies, 1, false);
    btSphereShape* sphere = a.scene->sphereShape(.5);
    const btVector3 v = btVector3(btScalar(kProjectileSpeed[0]), btScalar(kProjectileSpeed[1]), btScalar(kProjectileSpeed[2]));
    for (int i = 0; i < copies; ++i)
        addAwake(*a.scene, sphere, 1, cell(i, copies) + btVector3(-5, 10, 0))->setLinearVelocity(v);
    return a;
}

AccuracyScene accuracySlidingBox(WorldKind kind, const Config& config, int copies)
{
    AccuracyScene a = start(kind, config, "sliding_box", copies, 1, true);
    addSharedGround(*a.scene, copies, Material{1, 0});
    btBoxShape* box = a.scene->boxShape(btVector3(.5, .5, .5));
    const Material m{btScalar(kSlideFriction), 0};
    for (int i = 0; i < copies; ++i)
        addAwake(*a.scene, box, 1, cell(i, copies) + btVector3(-2, .5, 0), m)
            ->setLinearVelocity(btVector3(btScalar(kSlideSpeed), 0, 0));
    return a;
}

AccuracyScene accuracyBouncingSphere(WorldKind kind, const Config& config, int copies)
{
    AccuracyScene a = start(kind, config, "bouncing_sphere", copies, 1, true);
    // Bullet multiplies restitutions: ground 1 x sphere 0.5.
    addSharedGround(*a.scene, copies, Material{btScalar(0.5), 1});
    btSphereShape* sphere = a.scene->sphereShape(btScalar(kBounceRadius));
    const Material m{btScalar(0.5), btScalar(kBounceRestitution)};
    for (int i = 0; i < copies; ++i)
        addAwake(*a.scene, sphere, 1, cell(i, copies) + btVector3(0, btScalar(kBounceDropY), 0), m);
    return a;
}

AccuracyScene accuracyTumblingBox(WorldKind kind, const Config& config, int copies)
{
    AccuracyScene a = start(kind, config, "tumbling_box", copies, 1, false);
    a.scene->world().setGravity(btVector3(0, 0, 0));
    btBoxShape* box = a.scene->boxShape(btVector3(1, .5, .25));
    const btVector3 w = btVector3(btScalar(0.01), 1, btScalar(0.005)).normalized() * btScalar(kTumbleRate);
    for (int i = 0; i < copies; ++i) {
        btRigidBody* b = addAwake(*a.scene, box, 1, cell(i, copies) + btVector3(0, 5, 0));
        b->setGravity(btVector3(0, 0, 0));
        b->setAngularVelocity(w);
    }
    return a;
}

AccuracyScene accuracyStack(WorldKind kind, const Config& config, int copies, int height)
{
    AccuracyScene a = start(kind, config, "stack", copies, height, true);
    addSharedGround(*a.scene, copies, Material());
    btBoxShape* box = a.scene->boxShape(btVector3(.5, .5, .5));
    for (int i = 0; i < copies; ++i)
        for (int k = 0; k < height; ++k) {
            addAwake(*a.scene, box, 1, cell(i, copies) + btVector3(0, btScalar(.5 + k), 0));
            const int self = 1 + i * height + k;
            a.supports.push_back({self, k == 0 ? -1 : self - 1});
        }
    return a;
}

AccuracyScene accuracyPyramid(WorldKind kind, const Config& config, int copies, int base)
{
    const int perCopy = base * (base + 1) / 2;
    AccuracyScene a = start(kind, config, "pyramid", copies, perCopy, true);
    // A pyramid is 1.05 * base wide: copies kCopySpacing apart would overlap and explode.
    const double spacing = std::max(kCopySpacing, 1.05 * base + 10);
    addSharedGround(*a.scene, copies, Material(), spacing);
    btBoxShape* box = a.scene->boxShape(btVector3(.5, .5, .5));
    const double pitch = 1.05;  // 5 cm between neighbours in a row
    for (int i = 0; i < copies; ++i) {
        int rowStart = 1 + i * perCopy, below = -1;
        for (int row = 0; row < base; ++row) {
            const int n = base - row;
            for (int k = 0; k < n; ++k) {
                const double x = pitch * (k - 0.5 * (n - 1));
                addAwake(*a.scene, box, 1, cell(i, copies, spacing) + btVector3(btScalar(x), btScalar(.5 + row), 0));
                const int self = rowStart + k;
                if (row == 0) a.supports.push_back({self, -1});
                else {
                    a.supports.push_back({self, below + k});
                    a.supports.push_back({self, below + k + 1});
                }
            }
            below = rowStart;
            rowStart += n;
        }
    }
    return a;
}

AccuracyScene accuracyPile(WorldKind kind, const Config& config, int nx, int ny, int nz)
{
    AccuracyScene a = start(kind, config, "pile", 1, nx * ny * nz, true);
    const btScalar g = btScalar(kPileGroundHalfExtent);
    a.scene->addBody(a.scene->boxShape(btVector3(g, g, g)), 0, btVector3(0, -g, 0),
                     Material{btScalar(kPileFriction), 0});
    btBoxShape* box = a.scene->boxShape(btVector3(.5, .5, .5));
    for (const PileBody& p : pileLayout(nx, ny, nz)) {
        btTransform t;
        t.setOrigin(btVector3(btScalar(p.position[0]), btScalar(p.position[1]), btScalar(p.position[2])));
        t.setRotation(btQuaternion(btScalar(p.rotation[0]), btScalar(p.rotation[1]), btScalar(p.rotation[2]),
                                   btScalar(p.rotation[3])));
        addAwake(*a.scene, box, 1, t, Material{btScalar(kPileFriction), 0});
    }
    return a;
}

}  // namespace btgpu::scenes
