// offscreen_gl.cpp — EGL display and context set-up, framebuffer objects, readback.
#include "render/offscreen_gl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstring>

namespace btgpu::render {

struct OffscreenGl::State {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    GLuint drawFbo = 0, readFbo = 0, buffers[3] = {0, 0, 0};
    int width = 0, height = 0;
};

OffscreenGl::OffscreenGl() : m(std::make_unique<State>()) {}

OffscreenGl::~OffscreenGl()
{
    if (m->context != EGL_NO_CONTEXT) {
        glDeleteFramebuffers(1, &m->drawFbo);
        glDeleteFramebuffers(1, &m->readFbo);
        glDeleteRenderbuffers(3, m->buffers);
        eglMakeCurrent(m->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(m->display, m->context);
    }
    if (m->display != EGL_NO_DISPLAY) eglTerminate(m->display);
}

bool OffscreenGl::open(int width, int height, std::string* error)
{
    auto fail = [&](const std::string& why) {
        if (error) *error = why;
        return false;
    };
    // Mesa's surfaceless platform renders without any window system; other EGLs get their
    // default display.
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (getPlatformDisplay) m->display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (m->display == EGL_NO_DISPLAY) m->display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    EGLint major = 0, minor = 0;
    if (m->display == EGL_NO_DISPLAY || !eglInitialize(m->display, &major, &minor))
        return fail("no EGL display (Mesa's libegl-mesa0 and libgl1-mesa-dri provide one)");
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("EGL has no desktop OpenGL");
    const EGLint attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    eglChooseConfig(m->display, attributes, &config, 1, &configs);
    m->context = eglCreateContext(m->display, configs ? config : EGLConfig(nullptr), EGL_NO_CONTEXT, nullptr);
    if (m->context == EGL_NO_CONTEXT) return fail("EGL could not create an OpenGL context");
    if (!eglMakeCurrent(m->display, EGL_NO_SURFACE, EGL_NO_SURFACE, m->context))
        return fail("EGL cannot make a context current without a surface (EGL_KHR_surfaceless_context)");

    m->width = width, m->height = height;
    glGenRenderbuffers(3, m->buffers);
    GLint samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &samples);
    samples = samples >= 4 ? 4 : 0;
    glBindRenderbuffer(GL_RENDERBUFFER, m->buffers[0]);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, m->buffers[1]);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, m->buffers[2]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glGenFramebuffers(1, &m->drawFbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m->drawFbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m->buffers[0]);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m->buffers[1]);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return fail("framebuffer incomplete");
    glGenFramebuffers(1, &m->readFbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m->readFbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m->buffers[2]);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return fail("framebuffer incomplete");
    glBindFramebuffer(GL_FRAMEBUFFER, m->drawFbo);
    glViewport(0, 0, width, height);
    return true;
}

void OffscreenGl::makeCurrent()
{
    if (m->context == EGL_NO_CONTEXT) return;
    eglBindAPI(EGL_OPENGL_API);
    eglMakeCurrent(m->display, EGL_NO_SURFACE, EGL_NO_SURFACE, m->context);
    glBindFramebuffer(GL_FRAMEBUFFER, m->drawFbo);
}

void OffscreenGl::release()
{
    if (m->context != EGL_NO_CONTEXT) eglMakeCurrent(m->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

Image OffscreenGl::read()
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m->drawFbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m->readFbo);
    glBlitFramebuffer(0, 0, m->width, m->height, 0, 0, m->width, m->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m->readFbo);
    Image image;
    image.width = m->width, image.height = m->height;
    std::vector<std::uint8_t> bottomUp(size_t(m->width) * size_t(m->height) * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, m->width, m->height, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
    const size_t stride = size_t(m->width) * 3;
    image.rgb.resize(bottomUp.size());
    for (int y = 0; y < m->height; ++y)
        std::memcpy(&image.rgb[size_t(y) * stride], &bottomUp[size_t(m->height - 1 - y) * stride], stride);
    glBindFramebuffer(GL_FRAMEBUFFER, m->drawFbo);
    return image;
}

std::string OffscreenGl::renderer() const
{
    const GLubyte* r = glGetString(GL_RENDERER);
    return r ? reinterpret_cast<const char*>(r) : "";
}

}  // namespace btgpu::render
