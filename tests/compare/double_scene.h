// double_scene.h — the scene double_writer.cpp saves from Bullet's double build, and the values
// compare_test.cpp expects back from it (so the loader's double-precision records are tested).
#pragma once

namespace btgpu::double_scene {
constexpr int kBoxes = 8;                 // unit boxes in a row on a ground box, body i at x = 1.5 i
constexpr double kVelocityX = 0.5;        // m/s, every box
constexpr double kVelocityZPerBody = 0.25;
constexpr double kLinearDamping = 0.1;
constexpr double kAngularDamping = 0.2;
constexpr double kLinearSleep = 0.3;
constexpr double kAngularSleep = 0.4;
constexpr double kMass = 2.5;             // kg
}  // namespace btgpu::double_scene
