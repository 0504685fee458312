// demos_main.cpp — btgpu_demos: Bullet's example-browser demos run on stock Bullet and on btgpu
// side by side (ms/step of each, the path btgpu took and why, how far the two differ against
// stock's own chaos), with pictures: PNG frames rendered headless, or a GLFW window.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <sys/stat.h>

#include "demo_catalog.h"
#include "demo_run.h"
#if BTGPU_HAVE_RENDER
#include "demo_pictures.h"
#endif
#if BTGPU_HAVE_GLFW
#include "render/glfw_window.h"
#endif

using namespace btgpu;
using namespace btgpu::demos;

namespace {

void usage(FILE* out)
{
    std::fprintf(out,
                 "usage: btgpu_demos [--demo NAME|all] [--list] [--steps N] [--device gpu|cpu|<name>] [--no-chaos] [--worst K]\n"
                 "                   [--solver bullet|auto|soft] [--no-sleep] [--png DIR [--every N]] [--still FILE] [--size WxH] [--window]\n"
                 "  --demo NAME   one of --list (default basic); all runs each and prints a Markdown table\n"
                 "  --steps N     steps of 1/60 s (default: the demo's, 300)\n"
                 "  --no-chaos    skip the third world (stock nudged by 0.1 mm) that measures stock's own chaos\n"
                 "  --solver S    btgpu's solver: bullet (the default here: the bullet mode, Config::bulletMode(),\n"
                 "                whose answers follow stock's), auto (the library's default, the soft step) or soft\n"
                 "  --no-sleep    every dynamic body of every world DISABLE_DEACTIVATION (Bullet's BenchmarkDemo\n"
                 "                sleeps; this times it awake)\n"
                 "  --worst K     lists the K bodies that end farthest from stock (scene index, both centres)\n"
                 "  --png DIR     writes DIR/<demo>_<step>.png every N steps (default 30) and at the last, headless\n"
                 "  --still FILE  writes the last step's picture to FILE\n"
                 "  --size WxH    picture size (default 480x270)\n"
                 "  --window      shows btgpu's world in a window while it runs (GLFW builds only)\n");
}

struct Pictures {
    std::string dir, still;
    int every = 30, width = 480, height = 270;
    bool window = false;
    bool any() const { return !dir.empty() || !still.empty() || window; }
};

int runOne(const Demo& demo, const RunOptions& options, const Pictures& pictures, DemoResult& result)
{
    // Pictures and window each add a hook; both run when both are asked for.
    std::vector<StepHook> hooks;
#if BTGPU_HAVE_RENDER
    DemoPictures offscreen;
    const int steps = options.steps > 0 ? options.steps : demo.steps;
    if (!pictures.dir.empty() || !pictures.still.empty()) {
        std::string error;
        if (!offscreen.open(pictures.width, pictures.height, &error)) {
            std::fprintf(stderr, "btgpu_demos: cannot render headless: %s\n", error.c_str());
            return 1;
        }
        if (!pictures.dir.empty()) mkdir(pictures.dir.c_str(), 0755);
        hooks.push_back([&](int step, DemoWorld& world, const RayView& rays) {
            const bool frame = !pictures.dir.empty() && (step % pictures.every == 0 || step == steps);
            const bool still = !pictures.still.empty() && step == steps;
            if (!frame && !still) return;
            const render::Image image = offscreen.render(demo, world, rays);
            char name[64];
            std::snprintf(name, sizeof name, "_%05d.png", step);
            std::string error;
            if (frame && !render::writePng(pictures.dir + "/" + demo.name + name, image, &error))
                std::fprintf(stderr, "btgpu_demos: %s\n", error.c_str());
            if (still && !render::writePng(pictures.still, image, &error)) std::fprintf(stderr, "btgpu_demos: %s\n", error.c_str());
        });
    }
#endif
#if BTGPU_HAVE_GLFW
    render::GlfwWindow window;
    if (pictures.window) {
        std::string error;
        if (!window.open(pictures.width * 2, pictures.height * 2, "btgpu_demos: " + demo.name, &error)) {
            std::fprintf(stderr, "btgpu_demos: no window: %s\n", error.c_str());
            return 1;
        }
        hooks.push_back([&](int step, DemoWorld& world, const RayView& rays) {
            if (step == 0) window.setCamera(demoCamera(demo, world, pictures.width * 2, pictures.height * 2));
            if (demo.followFirstBody) window.follow(world.scene->body(1)->getWorldTransform().getOrigin());
            std::vector<render::ExtraShape> shapes;
            std::vector<render::Line> lines;
            demoExtras(world, rays, shapes, lines);
            window.draw(world.scene->world(), shapes, lines);
        });
    }
#endif
    StepHook hook;
    if (!hooks.empty())
        hook = [&hooks](int step, DemoWorld& world, const RayView& rays) {
            for (const StepHook& h : hooks) h(step, world, rays);
        };
    result = runDemo(demo, options, hook);
    printResult(result);
    return 0;
}

bool parseSize(const char* s, int& w, int& h)
{
    char tail = 0;
    return std::sscanf(s, "%dx%d%c", &w, &h, &tail) == 2 && w >= 16 && h >= 16 && w <= 8192 && h <= 8192;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string name = "basic";
    RunOptions options;
    Pictures pictures;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool hasValue = i + 1 < argc;
        if (a == "--demo" && hasValue) name = argv[++i];
        else if (a == "--steps" && hasValue) options.steps = std::max(1, std::atoi(argv[++i]));
        else if (a == "--device" && hasValue) options.config.device = argv[++i];
        else if (a == "--no-chaos") options.chaos = false;
        else if (a == "--no-sleep") options.noSleep = true;
        else if (a == "--solver" && hasValue) {
            const std::string v = argv[++i];
            if (v == "bullet") options.config.solver = SolverKind::BatchedPgs;
            else if (v == "auto") options.config.solver = SolverKind::Auto;
            else if (v == "soft") options.config.solver = SolverKind::SoftStep;
            else {
                std::fprintf(stderr, "btgpu_demos: --solver takes bullet, auto or soft, not %s\n", v.c_str());
                return 2;
            }
        }
        else if (a == "--worst" && hasValue) options.worst = std::max(0, std::atoi(argv[++i]));
        else if (a == "--png" && hasValue) pictures.dir = argv[++i];
        else if (a == "--still" && hasValue) pictures.still = argv[++i];
        else if (a == "--every" && hasValue) pictures.every = std::max(1, std::atoi(argv[++i]));
        else if (a == "--size" && hasValue) {
            if (!parseSize(argv[++i], pictures.width, pictures.height)) {
                std::fprintf(stderr, "btgpu_demos: --size wants WxH, e.g. 480x270\n");
                return 2;
            }
        } else if (a == "--window") pictures.window = true;
        else if (a == "--list") {
            for (const Demo& d : catalog()) std::printf("%-10s %s\n", d.name.c_str(), d.description.c_str());
            return 0;
        } else if (a == "--help" || a == "-h") {
            usage(stdout);
            return 0;
        } else {
            std::fprintf(stderr, "btgpu_demos: unknown argument %s\n", a.c_str());
            usage(stderr);
            return 2;
        }
    }
#if !BTGPU_HAVE_RENDER
    if (!pictures.dir.empty() || !pictures.still.empty()) {
        std::fprintf(stderr, "btgpu_demos: built without OpenGL/EGL or zlib (see CMake's message): no pictures\n");
        return 2;
    }
#endif
#if !BTGPU_HAVE_GLFW
    if (pictures.window) {
        std::fprintf(stderr, "btgpu_demos: built without GLFW (install libglfw3-dev and reconfigure): no --window; --png works headless\n");
        return 2;
    }
#endif
    if (name == "all") {
        if (!pictures.still.empty()) {
            std::fprintf(stderr, "btgpu_demos: --still names one file; use --png DIR with --demo all\n");
            return 2;
        }
        std::string table = markdownHeader();
        for (const Demo& d : catalog()) {
            DemoResult r;
            if (int rc = runOne(d, options, pictures, r)) return rc;
            table += markdownRow(r);
            std::printf("\n");
            std::fflush(stdout);
        }
        std::printf("%s", table.c_str());
        return 0;
    }
    const Demo* demo = find(name);
    if (!demo) {
        std::fprintf(stderr, "btgpu_demos: unknown demo '%s' (--list shows them)\n", name.c_str());
        return 2;
    }
    DemoResult r;
    return runOne(*demo, options, pictures, r);
}
