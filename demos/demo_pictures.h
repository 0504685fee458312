// demo_pictures.h — a demo's world as pictures: the camera framed on the demo's bodies (its yaw,
// pitch and zoom; following the chassis in the vehicle demo), the vehicle's wheels and the ray
// fan drawn beside the bodies, each frame rendered headless and returned as an Image.
#pragma once
#include <memory>
#include <string>

#include "demo_run.h"
#include "render/camera.h"
#include "render/offscreen_gl.h"
#include "render/world_renderer.h"

namespace btgpu::demos {

// The camera a demo's pictures use for `world` in a width x height picture.
render::Camera demoCamera(const Demo& demo, DemoWorld& world, int width, int height);
// What the renderer draws besides the world's bodies: wheels, rays (one in five).
void demoExtras(DemoWorld& world, const RayView& rays, std::vector<render::ExtraShape>& shapes,
                std::vector<render::Line>& lines);

class DemoPictures {
public:
    bool open(int width, int height, std::string* error);
    // Frames the camera on `world` (once, at the start) and renders it now.
    render::Image render(const Demo& demo, DemoWorld& world, const RayView& rays);
    const render::Camera& camera() const { return m_camera; }
    std::string renderer() const { return m_gl.renderer(); }

private:
    render::OffscreenGl m_gl;
    render::WorldRenderer m_renderer;
    render::Camera m_camera;
    int m_width = 0, m_height = 0;
    bool m_framed = false;
};

}  // namespace btgpu::demos
