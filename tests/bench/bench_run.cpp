// bench_run.cpp — the per-backend run loop and its statistics (see bench_run.h).
#include "bench_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace btgpu::bench {

namespace {

using Clock = std::chrono::steady_clock;

Percentiles percentiles(std::vector<double> v)
{
    Percentiles p;
    if (v.empty()) return p;
    std::sort(v.begin(), v.end());
    p.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    p.p90 = v[size_t(std::ceil(0.9 * v.size())) - 1];  // nearest rank
    p.max = v.back();
    return p;
}

// The lowest point of a body: its centre minus its extent along y in world space.
float lowestY(const Scene& scene, const BodySpec& b, const Pose& p)
{
    if (b.shape == ShapeKind::Sphere) return p.p[1] - b.radius;
    if (b.shape == ShapeKind::Plane) return p.p[1];
    float x = p.q[0], y = p.q[1], z = p.q[2], w = p.q[3];
    float r10 = 2 * (x * y + w * z), r11 = 1 - 2 * (x * x + z * z), r12 = 2 * (y * z - w * x);  // row y of R
    if (b.shape == ShapeKind::Hull) {
        const std::vector<float>& v = scene.hulls.at(size_t(b.hull)).points;
        float lowest = 0;
        for (size_t i = 0; i + 2 < v.size(); i += 3) {
            const float py = r10 * v[i] + r11 * v[i + 1] + r12 * v[i + 2];
            if (i == 0 || py < lowest) lowest = py;
        }
        return p.p[1] + lowest;
    }
    if (b.shape == ShapeKind::Capsule) return p.p[1] - std::fabs(r11) * b.half[1] - b.radius;  // axis: local y
    if (b.shape == ShapeKind::Compound) {
        // The lowest of its children's lowest points (box corners, sphere bottoms).
        float lowest = 0;
        bool first = true;
        for (const scenes::spec::ChildSpec& c : scene.compounds.at(size_t(b.compound)).children) {
            const float cy = r10 * c.pos[0] + r11 * c.pos[1] + r12 * c.pos[2];
            // A child's own rotation is identity in the bench's compounds; a rotated one is
            // bounded by its largest half extent.
            const bool turned = c.rot[3] != 1.0f;
            const float reach = c.shape == ShapeKind::Sphere ? c.radius
                                : turned ? std::sqrt(c.half[0] * c.half[0] + c.half[1] * c.half[1] + c.half[2] * c.half[2])
                                         : std::fabs(r10) * c.half[0] + std::fabs(r11) * c.half[1] + std::fabs(r12) * c.half[2];
            if (first || cy - reach < lowest) lowest = cy - reach;
            first = false;
        }
        return p.p[1] + lowest;
    }
    return p.p[1] - (std::fabs(r10) * b.half[0] + std::fabs(r11) * b.half[1] + std::fabs(r12) * b.half[2]);
}

bool finite(const Pose& p)
{
    for (float f : p.p) if (!std::isfinite(f)) return false;
    for (float f : p.q) if (!std::isfinite(f)) return false;
    return true;
}

}  // namespace

RunResult runBackend(Backend& backend, const Scene& scene, const Options& options, int frames, double budgetS)
{
    RunResult r;
    r.backend = backend.name();
    auto t0 = Clock::now();
    std::string why;
    if (!backend.setUp(scene, options, &why)) {
        r.skipped = why;
        r.device = backend.device();
        return r;
    }
    // The set-up (the app's own Bullet objects, added to the world) is timed apart from the
    // first step: at 1,000,000 bodies Bullet's broadphase insertions take longer than btgpu's
    // first step, and they are the same for stock.
    const auto t1 = Clock::now();
    r.setUpS = std::chrono::duration<double>(t1 - t0).count();
    FrameTime f0 = backend.step();
    (void)f0;
    r.firstStepS = std::chrono::duration<double>(Clock::now() - t1).count();
    r.device = backend.device();
    why = backend.checkAfterFirstFrame();
    if (!why.empty()) {
        r.skipped = why;
        r.notes = backend.notes();
        return r;
    }
    r.ran = true;
    r.minLowestY = 1e30f;
    std::vector<double> step, wb, total;
    std::map<std::string, std::vector<double>> stages;
    std::vector<Pose> poses;
    auto loopStart = Clock::now();
    auto lastProgress = loopStart;
    for (int frame = 1; frame <= frames; ++frame) {
        FrameTime t = backend.step();
        step.push_back(t.stepMs);
        total.push_back(t.stepMs + std::max(0.0, t.writebackMs));
        if (t.writebackMs >= 0) wb.push_back(t.writebackMs);
        bool lastFrame = frame == frames || std::chrono::duration<double>(Clock::now() - loopStart).count() > budgetS;
        backend.poses(poses);
        for (size_t i = 0; i < poses.size() && i < scene.bodies.size(); ++i) {
            const BodySpec& b = scene.bodies[i];
            if (b.mass <= 0 || !finite(poses[i])) continue;
            float low = lowestY(scene, b, poses[i]);
            if (low < r.minLowestY) r.minLowestY = low, r.minLowestFrame = frame;
        }
        FrameInfo info;
        backend.info(info, lastFrame);
        for (auto& [name, ms] : info.stageMs) stages[name].push_back(ms);
        r.framesRun = frame;
        if (lastFrame) {
            r.last = info;
            r.finalLowestY = 1e30f;
            for (size_t i = 0; i < poses.size() && i < scene.bodies.size(); ++i) {
                if (!finite(poses[i])) {
                    ++r.nanBodies;
                    continue;
                }
                if (scene.bodies[i].mass <= 0) continue;
                r.finalLowestY = std::min(r.finalLowestY, lowestY(scene, scene.bodies[i], poses[i]));
                if (poses[i].p[1] < 0) ++r.belowGround;
            }
            r.cutShort = frame < frames;
            break;
        }
        auto now = Clock::now();
        if (std::chrono::duration<double>(now - lastProgress).count() > 5) {
            std::fprintf(stderr, "  %s: frame %d/%d, last %.2f ms\n", r.backend.c_str(), frame, frames, total.back());
            lastProgress = now;
        }
    }
    r.stepMs = percentiles(step);
    r.writebackMs = percentiles(wb);
    r.totalMs = percentiles(total);
    for (auto& [name, v] : stages) r.stageMedianMs[name] = percentiles(v).median;
    r.notes = backend.notes();
    return r;
}

}  // namespace btgpu::bench
