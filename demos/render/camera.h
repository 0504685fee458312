// camera.h — an orbit camera (a target, yaw and pitch about it, a distance) with its OpenGL
// matrices, and the projection of a world point to a pixel with those same matrices: what the
// renderer draws with and what the render test checks the picture against.
#pragma once
#include <btBulletCollisionCommon.h>

namespace btgpu::render {

struct Camera {
    btVector3 target{0, 0, 0};
    float yawDegrees = 35;     // about +y, from +z towards +x
    float pitchDegrees = 25;   // above the horizon
    float distance = 10;       // m from the target
    float fovYDegrees = 45;
    int width = 480, height = 270;

    btVector3 eye() const;
    // Column-major 4x4 matrices as glLoadMatrixf takes them.
    void viewMatrix(float m[16]) const;
    void projectionMatrix(float m[16]) const;
    // Pixel (x right, y down from the top-left corner) of a world point; false when the point is
    // behind the camera or outside the picture.
    bool project(const btVector3& world, float& px, float& py) const;
    // Aims at the middle of the box and backs off until a sphere round it fills the picture.
    void frame(const btVector3& lo, const btVector3& hi);
};

// The box holding the world's dynamic bodies (their AABBs), or every object's when none move;
// statics much larger than the moving bodies (the ground) are left out so the camera frames
// what moves. False when the world is empty.
bool sceneBounds(const btCollisionWorld& world, btVector3& lo, btVector3& hi);

}  // namespace btgpu::render
