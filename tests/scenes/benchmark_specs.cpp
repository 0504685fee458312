// benchmark_specs.cpp — BenchmarkDemo's box pile, stacks and barrel hulls (benchmark_specs.h).
#include "benchmark_specs.h"

#include <cmath>

namespace btgpu::scenes::spec {

namespace {

// BenchmarkDemo's ground for tests 1-4: a static box of half extents (250, 50, 250), top at y = 0.
BodySpec benchGround()
{
    BodySpec g;
    g.half[0] = 250, g.half[1] = 50, g.half[2] = 250;
    g.pos[1] = -50;
    g.friction = 0.5f;
    return g;
}

// A dynamic box with Bullet's default material (BenchmarkDemo sets none).
BodySpec box(float half, float mass, float x, float y, float z)
{
    BodySpec b;
    b.half[0] = b.half[1] = b.half[2] = half;
    b.mass = mass;
    b.pos[0] = x, b.pos[1] = y, b.pos[2] = z;
    b.friction = 0.5f;
    return b;
}

Scene benchScene(const std::string& name)
{
    Scene s;
    s.name = name;
    s.bodies.push_back(benchGround());
    s.iterations = 5;  // BenchmarkDemo: "few solver iterations"
    return s;
}

// BenchmarkDemo's createTowerCircle at x = 25 into s: `rings` rings of 24 boxes on a circle of
// radius 1.3 * 24 / pi, each box turned to face the centre, every other ring turned by half a box.
void addBenchTower(Scene& s, int rings)
{
    const int around = 24;
    const float half = 1.0f, pi = 3.14159265358979f, radius = 1.3f * float(around) * half / pi;
    float y = half, angle = 0;
    for (int r = 0; r < rings; ++r) {
        for (int j = 0; j < around; ++j) {
            // rotate(rotY, (0, y, radius)) for a rotation by `angle` about y.
            BodySpec b = box(half, 1, 25 + radius * std::sin(angle), y, radius * std::cos(angle));
            b.rot[1] = std::sin(0.5f * angle);
            b.rot[3] = std::cos(0.5f * angle);
            s.bodies.push_back(b);
            angle += pi / (float(around) * 0.5f);
        }
        y += half * 2;
        angle += pi / float(around);
    }
}

}  // namespace

Scene makeBenchPile(int layers, int size)
{
    Scene s = benchScene("bench pile " + std::to_string(layers * size * size));
    const float cube = 1.0f, spacing = cube;
    float offset = -float(size) * (cube * 2 + spacing) * 0.5f, y = cube * 2;
    for (int k = 0; k < layers; ++k) {
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i)
                s.bodies.push_back(box(cube, 2, offset + float(i) * (cube * 2 + spacing), y,
                                       offset + float(j) * (cube * 2 + spacing)));
        offset -= 0.05f * spacing * float(size - 1);
        y += cube * 2 + spacing;
    }
    return s;
}

Scene makeBenchStacks()
{
    Scene s = benchScene("bench stacks");
    const float half = 1.0f;
    // createPyramid(-20, 0, 0), 12 high: layers of n x n boxes 1.02 apart (plus 0.1 mm).
    {
        const float space = 0.0001f, diff = half * 1.02f;
        float ox = -12 * (diff * 2 + space) * 0.5f, oz = ox, y = half;
        for (int n = 12; n > 0; --n) {
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    s.bodies.push_back(box(half, 1, -20 + ox + float(i) * (diff * 2 + space), y,
                                           oz + float(j) * (diff * 2 + space)));
            ox += diff, oz += diff, y += diff * 2 + space;
        }
    }
    // createWall at x = -2, 4, 10, 12 high: rows along z, each row one box shorter.
    for (float wx : {-2.0f, 4.0f, 10.0f}) {
        float offset = -12 * (half * 2) * 0.5f, y = half;
        for (int n = 12; n > 0; --n) {
            for (int i = 0; i < n; ++i) s.bodies.push_back(box(half, 1, wx, y, offset + float(i) * half * 2));
            offset += half, y += half * 2;
        }
    }
    addBenchTower(s, 8);
    return s;
}

Scene makeBenchTower(int rings)
{
    Scene s = benchScene("bench tower " + std::to_string(rings));
    addBenchTower(s, rings);
    return s;
}

Scene makeBenchHulls(int layers)
{
    Scene s = benchScene("bench hulls " + std::to_string(layers * 64));
    // A barrel like BenchmarkDemo's: rings of 8 points at y = -2, -1, 0, 1, 2 (radii 1.09 at
    // the ends, 1.82 at the belly), Bullet's default margin 0.04.
    HullSpec barrel;
    const float radii[5] = {1.087f, 1.6f, 1.822f, 1.6f, 1.087f};
    for (int ring = 0; ring < 5; ++ring)
        for (int k = 0; k < 8; ++k) {
            const float a = float(k) * 3.14159265358979f / 4;
            barrel.points.insert(barrel.points.end(), {radii[ring] * std::cos(a), -2.0f + float(ring), radii[ring] * std::sin(a)});
        }
    s.hulls.push_back(barrel);
    const int size = 8;
    const float cube = 1.5f;
    float spacing = cube, offset = -float(size) * (cube * 2 + spacing) * 0.5f, y = cube * 2;
    for (int k = 0; k < layers; ++k) {
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                BodySpec b = box(0, 1, offset + float(i) * (cube * 2 + spacing), y, offset + float(j) * (cube * 2 + spacing));
                b.shape = ShapeKind::Hull;
                b.hull = 0;
                s.bodies.push_back(b);
            }
        offset -= 0.05f * spacing * float(size - 1);
        spacing *= 1.01f;
        y += cube * 2 + spacing;
    }
    return s;
}

}  // namespace btgpu::scenes::spec
