// offscreen_gl.h — a headless OpenGL context (EGL on Mesa's surfaceless platform, no display or
// window needed) drawing into a 4x multisampled framebuffer object, read back as an Image.
#pragma once
#include <memory>
#include <string>

#include "render/png_image.h"

namespace btgpu::render {

class OffscreenGl {
public:
    OffscreenGl();
    ~OffscreenGl();
    OffscreenGl(const OffscreenGl&) = delete;
    OffscreenGl& operator=(const OffscreenGl&) = delete;

    // Makes a context current with a width x height framebuffer bound; false with `error`
    // naming what is missing (no EGL device, no desktop OpenGL, no framebuffer objects).
    bool open(int width, int height, std::string* error);
    // Makes this context current again (after another one, a window's, was).
    void makeCurrent();
    // Leaves no context current in this thread (so a window's GLX context can be made current).
    void release();
    // The picture drawn since the last read (resolved, rows top to bottom).
    Image read();
    std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

private:
    struct State;
    std::unique_ptr<State> m;
};

}  // namespace btgpu::render
