// glfw_window.h — btgpu_demos --window: a GLFW window showing a world as it is stepped, with an
// orbit camera the mouse turns (left drag), zooms (wheel) and pans (right drag); Esc or closing
// the window stops drawing (the run goes on to print its numbers). Built only where CMake finds
// GLFW; needs a display.
#pragma once
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/world_renderer.h"

struct GLFWwindow;

namespace btgpu::render {

class GlfwWindow {
public:
    ~GlfwWindow();
    bool open(int width, int height, const std::string& title, std::string* error);
    void setCamera(const Camera& camera) { m_camera = camera; }
    void follow(const btVector3& target) { m_camera.target = target; }
    // Draws the world and handles input; false once the window was closed.
    bool draw(const btCollisionWorld& world, const std::vector<ExtraShape>& extras, const std::vector<Line>& lines);

private:
    GLFWwindow* m_window = nullptr;
    Camera m_camera;
    WorldRenderer m_renderer;
    double m_lastX = 0, m_lastY = 0;
    bool m_closed = false;
};

}  // namespace btgpu::render
