// benchmark_specs.h — Bullet's BenchmarkDemo scenes 1, 2 and 4 (a 3,000-box pile, 1,000 boxes in
// stacks, walls and a tower, 960 convex barrels) as plain data (scene_specs.h), so the demos,
// the benchmark's backends and the tests build the very same bodies. Bullet's layouts are the
// facts; the ground is BenchmarkDemo's box of half extents (250, 50, 250) with its top at y = 0.
#pragma once
#include "scene_specs.h"

namespace btgpu::scenes::spec {

// Test 1: `layers` layers (Bullet: 47) of size x size (8) boxes of half extent 1, mass 2, 3 m
// apart, each layer 3 m higher and shifted by -0.35 m in x and z.
Scene makeBenchPile(int layers = 47, int size = 8);
// Test 2: a 12-high square pyramid at x = -20, three 12-high walls at x = -2, 4, 10 and a round
// tower of 8 rings of 24 boxes at x = 25 (1,076 unit boxes of half extent 1, mass 1).
Scene makeBenchStacks();
// Test 2's round tower alone: `rings` rings of 24 unit boxes (mass 1) on a circle of radius
// 1.3 * 24 / pi about (25, y, 0), each facing the axis, every other ring turned by half a box.
Scene makeBenchTower(int rings = 8);
// Test 4: `layers` (15) layers of 8 x 8 barrels (a 40-point convex hull, 4 m tall, 3.6 m across
// at its belly, polyhedral features on), mass 1, laid out as test 1 with cube size 1.5.
Scene makeBenchHulls(int layers = 15);

}  // namespace btgpu::scenes::spec
