// render_test.cpp — ctest label demo: the demos' pictures. One frame of a small btgpu scene is
// rendered headless and checked against the simulation (each body's projected centre shows the
// body's colour, a place with no body shows the background), the PNG writer round-trips, the
// shape meshes have the shapes' dimensions, and a demo runs on the GPU path with its picture.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <unistd.h>

#include "btgpu/btGpuDynamicsWorld.h"
#include "demo_pictures.h"
#include "render/png_image.h"
#include "render/shape_mesh.h"
#include "scenes/scenes.h"

using namespace btgpu;

namespace {

// Colour distance in [0, sqrt 3] between a pixel and a colour given in [0, 1].
double distance(const std::uint8_t* px, const btVector3& c)
{
    const double r = px[0] / 255.0 - c.x(), g = px[1] / 255.0 - c.y(), b = px[2] / 255.0 - c.z();
    return std::sqrt(r * r + g * g + b * b);
}

// Chromaticity (colour over its sum): lighting scales a face's colour, this keeps its hue.
btVector3 chroma(const btVector3& c)
{
    const btScalar s = c.x() + c.y() + c.z();
    return s > 0 ? c / s : c;
}
btVector3 chroma(const std::uint8_t* px) { return chroma(btVector3(px[0], px[1], px[2])); }

const btVector3 kBackground(render::kBackground[0], render::kBackground[1], render::kBackground[2]);

std::string tempDir()
{
    char name[] = "/tmp/btgpu_render_test_XXXXXX";
    const char* dir = mkdtemp(name);
    return dir ? dir : "/tmp";
}

}  // namespace

TEST(PngImage, WritesWhatItReadsBack)
{
    render::Image image;
    image.width = 37, image.height = 11;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            image.rgb.insert(image.rgb.end(), {std::uint8_t(x * 7), std::uint8_t(y * 23 + x), std::uint8_t((x * y) ^ 0x5a)});
    const std::string path = tempDir() + "/round_trip.png";
    std::string error;
    ASSERT_TRUE(render::writePng(path, image, &error)) << error;
    render::Image back;
    ASSERT_TRUE(render::readPng(path, back, &error)) << error;
    EXPECT_EQ(back.width, image.width);
    EXPECT_EQ(back.height, image.height);
    EXPECT_EQ(back.rgb, image.rgb);
    // A truncated file is refused, not read as a picture.
    ASSERT_EQ(truncate(path.c_str(), 60), 0);
    EXPECT_FALSE(render::readPng(path, back, &error));
    EXPECT_FALSE(error.empty());
}

TEST(ShapeMesh, HasTheShapesDimensions)
{
    auto bounds = [](const render::Mesh& m, btVector3& lo, btVector3& hi) {
        lo = btVector3(1e30f, 1e30f, 1e30f), hi = -lo;
        for (size_t i = 0; i < m.positions.size(); i += 3) {
            const btVector3 p(m.positions[i], m.positions[i + 1], m.positions[i + 2]);
            lo.setMin(p), hi.setMax(p);
        }
    };
    btVector3 lo, hi;
    const render::Mesh box = render::meshForShape(btBoxShape(btVector3(1, 2, 3)));
    EXPECT_EQ(box.triangles(), 12);
    bounds(box, lo, hi);
    EXPECT_NEAR(hi.x(), 1, 1e-5);
    EXPECT_NEAR(hi.y(), 2, 1e-5);
    EXPECT_NEAR(hi.z(), 3, 1e-5);
    EXPECT_NEAR(lo.x(), -1, 1e-5);

    const render::Mesh sphere = render::meshForShape(btSphereShape(0.5f));
    ASSERT_GT(sphere.triangles(), 100);
    for (size_t i = 0; i < sphere.positions.size(); i += 3)
        EXPECT_NEAR(btVector3(sphere.positions[i], sphere.positions[i + 1], sphere.positions[i + 2]).length(), 0.5, 1e-4);

    const render::Mesh capsule = render::meshForShape(btCapsuleShapeZ(0.25f, 1.0f));
    bounds(capsule, lo, hi);
    EXPECT_NEAR(hi.z(), 0.75, 1e-4);  // half height 0.5 plus the radius, along z
    EXPECT_NEAR(hi.x(), 0.25, 1e-3);

    const render::Mesh cone = render::meshForShape(btConeShape(0.4f, 1.0f));
    bounds(cone, lo, hi);
    EXPECT_NEAR(hi.y(), 0.5, 1e-4);
    EXPECT_NEAR(lo.y(), -0.5, 1e-4);

    btCompoundShape compound;
    btBoxShape unit(btVector3(0.5f, 0.5f, 0.5f));
    compound.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(2, 0, 0)), &unit);
    compound.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(-2, 0, 0)), &unit);
    const render::Mesh both = render::meshForShape(compound);
    EXPECT_EQ(both.triangles(), 24);
    bounds(both, lo, hi);
    EXPECT_NEAR(hi.x(), 2.5, 1e-5);
    EXPECT_NEAR(lo.x(), -2.5, 1e-5);

    std::vector<float> heights(5 * 5, 0.0f);
    btHeightfieldTerrainShape field(5, 5, heights.data(), 1, -1, 1, 1, PHY_FLOAT, false);
    EXPECT_EQ(render::meshForShape(field).triangles(), 2 * 4 * 4);

    const btVector3 hullPoints[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                     {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    btConvexHullShape hull(&hullPoints[0].x(), 8, sizeof(btVector3));
    EXPECT_EQ(render::meshForShape(hull).triangles(), 12);  // six square faces, two triangles each
}

TEST(Camera, ProjectsItsTargetToThePictureCentre)
{
    render::Camera c;
    c.width = 160, c.height = 90;
    c.target = btVector3(1, 2, 3);
    float x = 0, y = 0;
    ASSERT_TRUE(c.project(c.target, x, y));
    EXPECT_NEAR(x, 80, 1e-3);
    EXPECT_NEAR(y, 45, 1e-3);
    // Up in the world is up in the picture; behind the camera is not in it.
    ASSERT_TRUE(c.project(c.target + btVector3(0, 0.5f, 0), x, y));
    EXPECT_LT(y, 45);
    EXPECT_FALSE(c.project(c.eye() + (c.eye() - c.target), x, y));
}

// The frame shows the bodies where btgpu put them: three boxes falling side by side, the
// camera level with them, looking along -z.
TEST(RenderedFrame, HoldsTheBodiesWhereTheSimulationPutThem)
{
    scenes::ScenePtr scene = scenes::dropRow(scenes::WorldKind::Gpu);
    for (int i = 0; i < 30; ++i) {
        scene->step();
        ASSERT_TRUE(scene->gpuWorld()->isGpuPath()) << scene->report()->cpuPathReason;
    }
    for (int b = 1; b <= 3; ++b) ASSERT_LT(scene->body(b)->getWorldTransform().getOrigin().y(), 2.5);  // they fell

    render::OffscreenGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(160, 90, &error)) << error;
    render::Camera camera;
    camera.width = 160, camera.height = 90;
    camera.target = btVector3(0, 1.5f, 0);
    camera.yawDegrees = 0, camera.pitchDegrees = 0, camera.distance = 10;
    render::WorldRenderer renderer;
    renderer.draw(scene->world(), camera);
    const render::Image frame = gl.read();
    ASSERT_EQ(frame.width, 160);
    ASSERT_EQ(int(frame.rgb.size()), 160 * 90 * 3);

    // Not blank: the ground fills the lower half, the boxes part of the middle.
    int drawn = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) drawn += distance(frame.at(x, y), kBackground) > 0.05;
    EXPECT_GT(drawn, frame.width * frame.height / 4);
    EXPECT_LT(drawn, frame.width * frame.height * 9 / 10);

    const btCollisionObjectArray& objects = scene->world().getCollisionObjectArray();
    for (int b = 1; b <= 3; ++b) {
        const btRigidBody* body = scene->body(b);
        float px = 0, py = 0;
        ASSERT_TRUE(camera.project(body->getWorldTransform().getOrigin(), px, py)) << "body " << b;
        const std::uint8_t* pixel = frame.at(int(px), int(py));
        const btVector3 own = render::objectColour(*body, scene->worldIndex(body));
        EXPECT_GT(distance(pixel, kBackground), 0.1) << "body " << b << " at pixel " << px << ", " << py;
        // Its own hue, not another body's or the ground's.
        const double mine = (chroma(pixel) - chroma(own)).length();
        for (int other = 0; other < objects.size(); ++other) {
            if (objects[other] == body) continue;
            const btVector3 theirs = render::objectColour(*objects[other], other);
            if ((chroma(theirs) - chroma(own)).length() < 0.05) continue;  // same palette entry
            EXPECT_LT(mine, (chroma(pixel) - chroma(theirs)).length()) << "body " << b << " vs object " << other;
        }
    }
    // Nothing is 3 m above the boxes: the sky there.
    float px = 0, py = 0;
    ASSERT_TRUE(camera.project(btVector3(0, 5, 0), px, py));
    EXPECT_LT(distance(frame.at(int(px), int(py)), kBackground), 0.02);
    // And nothing where the boxes were released (3 m up at x = 2): they left it.
    ASSERT_TRUE(camera.project(btVector3(2, 3, 0), px, py));
    EXPECT_LT(distance(frame.at(int(px), int(py)), kBackground), 0.02);
}

// A demo as btgpu_demos runs it (5 steps of BasicDemo), its picture written and read back.
TEST(Demo, BasicRunsOnTheGpuPathAndPicturesIt)
{
    const demos::Demo* demo = demos::find("basic");
    ASSERT_NE(demo, nullptr);
    demos::DemoPictures pictures;
    std::string error;
    ASSERT_TRUE(pictures.open(96, 54, &error)) << error;
    const std::string path = tempDir() + "/basic.png";
    demos::RunOptions options;
    options.steps = 5;
    const demos::DemoResult r = demos::runDemo(*demo, options, [&](int step, demos::DemoWorld& world, const demos::RayView& rays) {
        if (step == 5) ASSERT_TRUE(render::writePng(path, pictures.render(*demo, world, rays), &error)) << error;
    });
    EXPECT_TRUE(r.gpuEveryStep) << r.cpuReason;
    EXPECT_EQ(r.dynamicBodies, 125);
    EXPECT_LT(r.maxDiff, 1e-3);  // 5 steps of free fall: the same
    EXPECT_GE(r.chaosMean, 0);
    render::Image back;
    ASSERT_TRUE(render::readPng(path, back, &error)) << error;
    int drawn = 0;
    for (int y = 0; y < back.height; ++y)
        for (int x = 0; x < back.width; ++x) drawn += distance(back.at(x, y), kBackground) > 0.05;
    EXPECT_GT(drawn, back.width * back.height / 20);
}

// Every demo of btgpu_demos builds and steps; each is on the GPU path but the two whose features
// the GPU path does not serve yet, which say why (actions and compound shapes, each being put on
// the GPU elsewhere: either may then run on the GPU path).
TEST(Demo, EachTakesThePathItShouldAndSaysWhy)
{
    // Dynamic bodies of each demo: Bullet's counts where the demo is Bullet's (BenchmarkDemo 1: 8 x 8 x
    // 47; 2: 650 + 3 x 78 + 192; 3: 136 x 11; 4: 8 x 8 x 15; 5: 10 x 10 x 10; BasicDemo 5 x 5 x 5).
    const std::map<std::string, int> bodies = {{"basic", 125},    {"pile", 3008},     {"stacks", 1076},  {"ragdolls", 1496},
                                               {"hulls", 960},    {"mixed", 1000},    {"landscape", 1000}, {"raycast", 1000},
                                               {"voronoi", 90},   {"ragdoll", 99},    {"vehicle", 9},    {"compound", 24}};
    ASSERT_EQ(demos::catalog().size(), bodies.size());
    for (const demos::Demo& demo : demos::catalog()) {
        demos::RunOptions options;
        options.steps = 2;
        options.chaos = false;
        const demos::DemoResult r = demos::runDemo(demo, options);
        EXPECT_TRUE(r.finite) << demo.name;
        ASSERT_EQ(bodies.count(demo.name), 1u) << demo.name;
        EXPECT_EQ(r.dynamicBodies, bodies.at(demo.name)) << demo.name;
        if (demo.name == "vehicle") {
            if (!r.gpuEveryStep) EXPECT_NE(r.cpuReason.find("actions"), std::string::npos) << r.cpuReason;
        } else if (demo.name == "compound") {
            if (!r.gpuEveryStep) EXPECT_NE(r.cpuReason.find("Compound"), std::string::npos) << r.cpuReason;
        } else {
            EXPECT_TRUE(r.gpuEveryStep) << demo.name << ": " << r.cpuReason;
        }
    }
}

// btgpu_demos' --solver and --no-sleep: the solver the world ran is the one asked for (the bullet
// mode unless told), and every dynamic body of btgpu's world stays awake on request.
TEST(Demo, SolverAndNoSleepTakeEffect)
{
    const demos::Demo* demo = demos::find("voronoi");
    ASSERT_NE(demo, nullptr);
    demos::RunOptions options;
    options.steps = 3;
    options.chaos = false;
    const demos::DemoResult bullet = demos::runDemo(*demo, options);
    EXPECT_EQ(bullet.solver, scenes::solverName(SolverKind::BatchedPgs));
    options.config.solver = SolverKind::Auto;
    options.noSleep = true;
    int awake = 0, dynamic = 0;
    const demos::DemoResult soft = demos::runDemo(*demo, options, [&](int step, demos::DemoWorld& world, const demos::RayView&) {
        if (step != 3) return;
        for (const btRigidBody* b : world.scene->bodies()) {
            if (b->isStaticOrKinematicObject()) continue;
            ++dynamic;
            awake += b->getActivationState() == DISABLE_DEACTIVATION;
        }
    });
    EXPECT_TRUE(soft.gpuEveryStep) << soft.cpuReason;
    EXPECT_EQ(soft.solver, scenes::solverName(SolverKind::SoftStep));
    EXPECT_EQ(dynamic, 90);
    EXPECT_EQ(awake, dynamic);
}
