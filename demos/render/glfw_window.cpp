// glfw_window.cpp — the window, its context and the mouse orbit (glfw_window.h).
#include "render/glfw_window.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

namespace btgpu::render {

namespace {
float g_scroll = 0;  // wheel clicks since the last frame (GLFW reports them by callback)
void onScroll(GLFWwindow*, double, double dy) { g_scroll += float(dy); }
}  // namespace

GlfwWindow::~GlfwWindow()
{
    if (m_window) glfwDestroyWindow(m_window);
    if (m_window) glfwTerminate();
}

bool GlfwWindow::open(int width, int height, const std::string& title, std::string* error)
{
    if (!glfwInit()) {
        if (error) *error = "GLFW cannot start (no display?)";
        return false;
    }
    glfwWindowHint(GLFW_SAMPLES, 4);
    m_window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!m_window) {
        if (error) *error = "GLFW cannot open a window (no display?)";
        glfwTerminate();
        return false;
    }
    glfwMakeContextCurrent(m_window);
    glfwSwapInterval(0);  // the simulation sets the pace
    glfwSetScrollCallback(m_window, onScroll);
    glfwGetCursorPos(m_window, &m_lastX, &m_lastY);
    glfwMakeContextCurrent(nullptr);  // draw() makes it current when it draws
    return true;
}

bool GlfwWindow::draw(const btCollisionWorld& world, const std::vector<ExtraShape>& extras, const std::vector<Line>& lines)
{
    if (m_closed || !m_window) return false;
    glfwMakeContextCurrent(m_window);  // the headless pictures may have made theirs current
    glfwPollEvents();
    if (glfwWindowShouldClose(m_window) || glfwGetKey(m_window, GLFW_KEY_ESCAPE) == GLFW_PRESS) {
        m_closed = true;
        glfwHideWindow(m_window);
        return false;
    }
    double x = 0, y = 0;
    glfwGetCursorPos(m_window, &x, &y);
    const float dx = float(x - m_lastX), dy = float(y - m_lastY);
    m_lastX = x, m_lastY = y;
    if (glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
        m_camera.yawDegrees -= 0.3f * dx;
        m_camera.pitchDegrees = std::clamp(m_camera.pitchDegrees + 0.3f * dy, -89.0f, 89.0f);
    }
    if (glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
        const btVector3 forward = (m_camera.target - m_camera.eye()).normalized();
        const btVector3 right = forward.cross(btVector3(0, 1, 0)).safeNormalize();
        const btVector3 up = right.cross(forward);
        const float scale = 0.002f * m_camera.distance;
        m_camera.target += (-right * dx + up * dy) * scale;
    }
    m_camera.distance *= std::pow(0.9f, g_scroll);
    g_scroll = 0;
    glfwGetFramebufferSize(m_window, &m_camera.width, &m_camera.height);
    m_camera.width = std::max(1, m_camera.width), m_camera.height = std::max(1, m_camera.height);
    m_renderer.draw(world, m_camera, extras, lines);
    glfwSwapBuffers(m_window);
    glfwMakeContextCurrent(nullptr);  // the headless pictures (--png) make theirs current next
    return true;
}

}  // namespace btgpu::render
