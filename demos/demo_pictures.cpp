// demo_pictures.cpp — camera set-up and extras per demo (demo_pictures.h).
#include "demo_pictures.h"

#include <BulletDynamics/Vehicle/btRaycastVehicle.h>

namespace btgpu::demos {

render::Camera demoCamera(const Demo& demo, DemoWorld& world, int width, int height)
{
    render::Camera c;
    c.width = width, c.height = height;
    c.yawDegrees = demo.yawDegrees, c.pitchDegrees = demo.pitchDegrees;
    btVector3 lo, hi;
    if (demo.followFirstBody && world.scene->bodies().size() > 1) {
        const btVector3 p = world.scene->body(1)->getWorldTransform().getOrigin();
        c.frame(p - btVector3(4, 2, 4), p + btVector3(4, 2, 4));
    } else if (render::sceneBounds(world.scene->world(), lo, hi)) {
        c.frame(lo, hi);
    }
    c.distance *= demo.zoom;
    return c;
}

void demoExtras(DemoWorld& world, const RayView& rays, std::vector<render::ExtraShape>& shapes,
                std::vector<render::Line>& lines)
{
    if (world.vehicle) {
        // One cylinder shape for all wheels (their axles along the wheel frame's x).
        static btCylinderShapeX wheel(btVector3(0.2f, 0.5f, 0.5f));
        for (int i = 0; i < world.vehicle->getNumWheels(); ++i) {
            const btWheelInfo& w = world.vehicle->getWheelInfo(i);
            shapes.push_back({&wheel, w.m_worldTransform, btVector3(0.12f, 0.12f, 0.12f)});
        }
    }
    // Every hit as a 1.5 m pin standing on the hit point; one ray in 25 drawn whole.
    if (rays.fan && rays.fractions)
        for (size_t i = 0; i < rays.fan->from.size() && i < rays.fractions->size(); ++i) {
            const btVector3& a = rays.fan->from[i];
            const btVector3 b = a + (rays.fan->to[i] - a) * btScalar((*rays.fractions)[i]);
            if (i % 25 == 0) lines.push_back({a, b, btVector3(0.9f, 0.15f, 0.1f)});
            if ((*rays.fractions)[i] < 1) lines.push_back({b, b + btVector3(0, 1.5f, 0), btVector3(0.9f, 0.1f, 0.1f)});
        }
}

bool DemoPictures::open(int width, int height, std::string* error)
{
    m_width = width, m_height = height;
    const bool ok = m_gl.open(width, height, error);
    m_gl.release();  // render() makes it current when it draws
    return ok;
}

render::Image DemoPictures::render(const Demo& demo, DemoWorld& world, const RayView& rays)
{
    if (!m_framed || demo.followFirstBody) {
        m_camera = demoCamera(demo, world, m_width, m_height);
        m_framed = true;
    }
    m_gl.makeCurrent();
    std::vector<render::ExtraShape> shapes;
    std::vector<render::Line> lines;
    demoExtras(world, rays, shapes, lines);
    m_renderer.draw(world.scene->world(), m_camera, shapes, lines);
    render::Image image = m_gl.read();
    m_gl.release();  // a window (--window with --png) makes its own context current next
    return image;
}

}  // namespace btgpu::demos
