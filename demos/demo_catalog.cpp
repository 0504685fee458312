// demo_catalog.cpp — the demo list (demo_catalog.h).
#include "demo_catalog.h"

#include "scenes/demo_scenes.h"
#include "scenes/joint_scenes.h"
#include "scenes/mesh_scenes.h"

namespace btgpu::demos {

namespace {

using scenes::WorldKind;

// A demo whose world is just a scene of the library.
std::function<DemoWorld(WorldKind, const Config&)> plain(std::function<scenes::ScenePtr(WorldKind, const Config&)> make)
{
    return [make](WorldKind kind, const Config& config) { return DemoWorld{make(kind, config), nullptr}; };
}

}  // namespace

const std::vector<Demo>& catalog()
{
    static const std::vector<Demo> demos = [] {
        std::vector<Demo> d;
        d.push_back({"basic", "BasicDemo: 125 boxes of 0.2 m dropped on a ground box", plain(scenes::basicDemo), 300,
                     false, 35, 20, 1.0f});
        d.push_back({"pile", "BenchmarkDemo 1: 3,008 boxes falling into a pile",
                     plain([](WorldKind k, const Config& c) { return scenes::benchPile(k, c); }), 300, false, 35, 20, 0.9f});
        d.push_back({"stacks", "BenchmarkDemo 2: 1,076 boxes in a pyramid, three walls and a round tower",
                     plain([](WorldKind k, const Config& c) { return scenes::benchStacks(k, c); }), 300, false, 15, 20, 0.8f});
        d.push_back({"ragdolls", "BenchmarkDemo 3: 136 ragdolls of capsules at scale 3.5 (5 hinges, 5 cone-twists each) in a stepped heap",
                     plain([](WorldKind k, const Config& c) { return scenes::benchRagdolls(k, c); }), 300, false, 30, 35, 0.45f});
        d.push_back({"hulls", "BenchmarkDemo 4: 960 convex-hull barrels falling into a pile",
                     plain([](WorldKind k, const Config& c) { return scenes::benchHulls(k, c); }), 300, false, 35, 20, 0.9f});
        d.push_back({"mixed", "BenchmarkDemo 5: 1,000 boxes, spheres and capsules of three sizes",
                     plain([](WorldKind k, const Config& c) { return scenes::benchMixedShapes(k, c); }), 300, false, 35, 25, 0.8f});
        d.push_back({"landscape", "BenchmarkDemo 6: 1,000 boxes, spheres and hulls on a 20,000-triangle landscape",
                     plain([](WorldKind k, const Config& c) { return scenes::landscape(k, c, 1000); }), 300, false, 35, 30, 0.8f});
        d.push_back({"raycast", "BenchmarkDemo 7: the landscape with 500 rays cast on it every step",
                     plain([](WorldKind k, const Config& c) { return scenes::landscape(k, c, 1000); }), 300, true, 35, 35, 1.0f});
        d.push_back({"voronoi", "BenchmarkDemo 8: a cube broken into 90 Voronoi pieces (convex hulls) dropped",
                     plain([](WorldKind k, const Config& c) { return scenes::voronoiPieces(k, c); }), 300, false, 35, 25, 0.6f});
        d.push_back({"ragdoll", "RagdollDemo: 9 ragdolls of capsules, hinges and cone-twists",
                     plain([](WorldKind k, const Config& c) { return scenes::capsuleRagdolls(k, c, 9); }), 300, false, 35, 30, 0.75f});
        Demo vehicle{"vehicle", "VehicleDemo: a btRaycastVehicle driving over a heightfield into crates",
                     [](WorldKind k, const Config& c) {
                         DemoWorld w;
                         w.scene = scenes::raycastVehicle(k, c, &w.vehicle);
                         return w;
                     },
                     300, false, 160, 20, 1.0f};
        vehicle.followFirstBody = true;
        d.push_back(vehicle);
        d.push_back({"compound", "CompoundDemo: 24 compound bodies (tables, L-shapes, dumbbells) in a heap",
                     plain([](WorldKind k, const Config& c) { return scenes::compoundPile(k, c); }), 300, false, 35, 25, 0.6f});
        return d;
    }();
    return demos;
}

const Demo* find(const std::string& name)
{
    for (const Demo& d : catalog())
        if (d.name == name) return &d;
    return nullptr;
}

}  // namespace btgpu::demos
