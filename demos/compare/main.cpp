// main.cpp — btgpu_compare: a saved Bullet scene (.bullet) on stock Bullet and on btgpu,
// judged against stock's own chaos. Exit 0 within it on the GPU path, 1 outside it, 2 bad
// input, 3 when the btgpu world ran on the CPU path.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "compare/compare_report.h"
#include "compare/compare_run.h"

using namespace btgpu::compare;

static const char* kUsage =
    "usage: btgpu_compare scene.bullet [--steps N] [--dt S] [--out DIR] [--device D] [--solver S] [--every-step] [--quiet]\n"
    "  Loads a .bullet file (btgpu::saveWorld, or any Bullet app's btDefaultSerializer + world->serialize())\n"
    "  into stock btDiscreteDynamicsWorld and into btGpuDynamicsWorld, runs both and stock again with every\n"
    "  start nudged by 0.1 mm (8 fixed seeds), and reports how far btgpu is from stock relative to that chaos.\n"
    "  --steps N   steps to run (default 300)\n"
    "  --dt S      fixed step in seconds (default: the file's own, else 1/60)\n"
    "  --out DIR   write compare.md, timeline.csv, bodies.csv, divergence.svg there\n"
    "  --device D  OpenCL device for btgpu: gpu, cpu or a name substring (as BTGPU_DEVICE)\n"
    "  --solver S  btgpu's solver: bullet (default: Config::bulletMode(), the mode whose answers follow\n"
    "              stock's), auto (the library's default: the soft step, which holds stiff scenes up where\n"
    "              stock's solver lets them sag or fall, so it may land outside stock's chaos there) or soft\n"
    "  --every-step  judge the aggregates after every step, not only at the end\n"
    "  exit: 0 within stock's chaos on the GPU path, 1 outside it, 2 bad input, 3 ran on the CPU path\n";

static bool number(const char* s, double& out)
{
    char* end = nullptr;
    out = std::strtod(s, &end);
    return end && end != s && *end == 0;
}

int main(int argc, char** argv)
{
    CompareOptions o;
    o.verbose = true;
    std::string out;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](const char* name) -> const char* {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "btgpu_compare: %s needs a value\n%s", name, kUsage);
                std::exit(kBadInput);
            }
            return argv[++i];
        };
        double v = 0;
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (a == "--steps") {
            if (!number(value("--steps"), v) || v < 1 || v > 1e7 || v != double(int(v))) {
                std::fprintf(stderr, "btgpu_compare: --steps takes a whole number from 1 to 10^7, not %s\n", argv[i]);
                return kBadInput;
            }
            o.steps = int(v);
        } else if (a == "--dt") {
            if (!number(value("--dt"), v) || !(v > 0) || v > 1) {
                std::fprintf(stderr, "btgpu_compare: --dt takes seconds in (0, 1], not %s\n", argv[i]);
                return kBadInput;
            }
            o.dt = v;
        } else if (a == "--out") {
            out = value("--out");
        } else if (a == "--device") {
            o.config.device = value("--device");
        } else if (a == "--solver") {
            const std::string s = value("--solver");
            if (s == "bullet") o.config.solver = btgpu::SolverKind::BatchedPgs;
            else if (s == "auto") o.config.solver = btgpu::SolverKind::Auto;
            else if (s == "soft") o.config.solver = btgpu::SolverKind::SoftStep;
            else {
                std::fprintf(stderr, "btgpu_compare: --solver takes bullet, auto or soft, not %s\n%s", s.c_str(), kUsage);
                return kBadInput;
            }
        } else if (a == "--every-step") {
            o.everyStep = true;
        } else if (a == "--quiet") {
            o.verbose = false;
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "btgpu_compare: unknown option %s\n%s", a.c_str(), kUsage);
            return kBadInput;
        } else if (o.path.empty()) {
            o.path = a;
        } else {
            std::fprintf(stderr, "btgpu_compare: one scene file at a time (%s and %s)\n", o.path.c_str(), a.c_str());
            return kBadInput;
        }
    }
    if (o.path.empty()) {
        std::fputs(kUsage, stderr);
        return kBadInput;
    }
    const CompareResult r = runCompare(o);
    if (r.exitCode == kBadInput) {
        std::fputs(summary(r).c_str(), stderr);
        return kBadInput;
    }
    std::fputs(summary(r).c_str(), stdout);
    if (!out.empty()) {
        const std::string e = writeOutputs(r, out);
        if (!e.empty()) {
            std::fprintf(stderr, "btgpu_compare: %s\n", e.c_str());
            return kBadInput;
        }
        std::printf("  wrote %s/compare.md, timeline.csv, bodies.csv, divergence.svg\n", out.c_str());
    }
    return r.exitCode;
}
