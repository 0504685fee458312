// camera.cpp — look-at and perspective matrices (as gluLookAt / gluPerspective build them).
#include "render/camera.h"

#include <algorithm>
#include <cmath>

namespace btgpu::render {

namespace {
constexpr float kNear = 0.05f;
float radians(float d) { return d * float(SIMD_PI) / 180.0f; }
}  // namespace

btVector3 Camera::eye() const
{
    const float yaw = radians(yawDegrees), pitch = radians(pitchDegrees);
    return target + distance * btVector3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
}

void Camera::viewMatrix(float m[16]) const
{
    const btVector3 e = eye();
    const btVector3 f = (target - e).normalized();
    const btVector3 s = f.cross(btVector3(0, 1, 0)).normalized();
    const btVector3 u = s.cross(f);
    const float v[16] = {s.x(), u.x(), -f.x(), 0, s.y(), u.y(), -f.y(), 0, s.z(), u.z(), -f.z(), 0,
                         -s.dot(e), -u.dot(e), f.dot(e), 1};
    for (int i = 0; i < 16; ++i) m[i] = v[i];
}

void Camera::projectionMatrix(float m[16]) const
{
    const float farPlane = std::max(100.0f, 4 * distance);
    const float f = 1.0f / std::tan(radians(fovYDegrees) / 2), aspect = float(width) / float(height);
    for (int i = 0; i < 16; ++i) m[i] = 0;
    m[0] = f / aspect;
    m[5] = f;
    m[10] = (farPlane + kNear) / (kNear - farPlane);
    m[11] = -1;
    m[14] = 2 * farPlane * kNear / (kNear - farPlane);
}

bool Camera::project(const btVector3& p, float& px, float& py) const
{
    float v[16], pr[16];
    viewMatrix(v);
    projectionMatrix(pr);
    float eyeP[4], clip[4];
    const float in[4] = {p.x(), p.y(), p.z(), 1};
    for (int r = 0; r < 4; ++r) eyeP[r] = v[r] * in[0] + v[4 + r] * in[1] + v[8 + r] * in[2] + v[12 + r] * in[3];
    for (int r = 0; r < 4; ++r) clip[r] = pr[r] * eyeP[0] + pr[4 + r] * eyeP[1] + pr[8 + r] * eyeP[2] + pr[12 + r] * eyeP[3];
    if (clip[3] <= kNear) return false;
    const float nx = clip[0] / clip[3], ny = clip[1] / clip[3];
    px = (nx * 0.5f + 0.5f) * float(width);
    py = (0.5f - ny * 0.5f) * float(height);
    return px >= 0 && py >= 0 && px < float(width) && py < float(height);
}

void Camera::frame(const btVector3& lo, const btVector3& hi)
{
    target = (lo + hi) * 0.5f;
    const float radius = std::max(0.5f, float((hi - lo).length() * 0.5f));
    const float aspect = float(width) / float(height);
    const float halfFov = radians(fovYDegrees) / 2, halfFovX = std::atan(std::tan(halfFov) * aspect);
    distance = radius / std::sin(std::min(halfFov, halfFovX)) * 0.85f;
}

bool sceneBounds(const btCollisionWorld& world, btVector3& lo, btVector3& hi)
{
    const btCollisionObjectArray& objects = world.getCollisionObjectArray();
    bool any = false;
    btVector3 dlo(0, 0, 0), dhi(0, 0, 0);
    for (int i = 0; i < objects.size(); ++i) {
        const btCollisionObject* o = objects[i];
        if (o->isStaticOrKinematicObject()) continue;
        btVector3 a, b;
        o->getCollisionShape()->getAabb(o->getWorldTransform(), a, b);
        if (!any) dlo = a, dhi = b, any = true;
        else dlo.setMin(a), dhi.setMax(b);
    }
    if (any) {
        // Down to the static ground under the bodies (where they will land) and a little wider
        // (where piles spread).
        float ground = -1e30f;
        for (int i = 0; i < objects.size(); ++i) {
            const btCollisionObject* o = objects[i];
            if (!o->isStaticObject()) continue;
            btVector3 a, b;
            o->getCollisionShape()->getAabb(o->getWorldTransform(), a, b);
            const bool under = a.x() <= dhi.x() && b.x() >= dlo.x() && a.z() <= dhi.z() && b.z() >= dlo.z();
            if (under && b.y() <= dlo.y() + 0.01f) ground = std::max(ground, float(b.y()));
        }
        if (ground > -1e29f) dlo.setY(ground);
        const btVector3 grow = (dhi - dlo) * 0.15f;
        lo = dlo - btVector3(grow.x(), 0, grow.z()), hi = dhi + btVector3(grow.x(), 0, grow.z());
        return true;
    }
    for (int i = 0; i < objects.size(); ++i) {
        btVector3 a, b;
        objects[i]->getCollisionShape()->getAabb(objects[i]->getWorldTransform(), a, b);
        a.setMax(btVector3(-100, -100, -100)), b.setMin(btVector3(100, 100, 100));
        if (!any) lo = a, hi = b, any = true;
        else lo.setMin(a), hi.setMax(b);
    }
    return any;
}

}  // namespace btgpu::render
