// compare_report.cpp — renders a CompareResult; the verdict's words match the exit code.
#include "compare/compare_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tolerances.h"

namespace btgpu::compare {
namespace {

std::string fmt(const char* f, double v)
{
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}
std::string g6(double v) { return fmt("%.6g", v); }
std::string joined(const std::vector<std::string>& v)
{
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? "none" : s;
}
std::string vec(const btVector3& v)
{
    return "(" + g6(v.x() + 0.0) + ", " + g6(v.y() + 0.0) + ", " + g6(v.z() + 0.0) + ")";  // + 0.0: no "-0"
}

const char* verdictWords(int code)
{
    switch (code) {
    case kWithinChaos: return "btgpu stayed within stock Bullet's own chaos, on the GPU path every step";
    case kOutsideChaos: return "btgpu left stock Bullet's chaos band (on the GPU path every step)";
    case kCpuPath: return "the btgpu world ran on the CPU path: nothing of the GPU pipeline was compared";
    default: return "bad input";
    }
}

}  // namespace

const char* const* notInFile()
{
    static const char* const items[] = {
        "rigid-body flags (`BT_DISABLE_WORLD_GRAVITY`, the gyroscopic terms): Bullet 3.24's default, the implicit gyroscopic term",
        "spinning friction (`setSpinningFriction`): 0",
        "`m_additionalDamping` and its factors: in the file but settable only through construction info",
        "which objects a body ignores (`setIgnoreCollisionCheck`)",
        "motion states, user pointers and indices; kinematic bodies keep still (the app moved them through their motion state)",
        "forces the app applies every step, actions (vehicles, character controllers), contact callbacks",
        "the dispatcher, broadphase and solver the app chose and their settings: here Bullet's defaults "
        "(btDefaultCollisionConfiguration, btCollisionDispatcher, btDbvtBroadphase, btSequentialImpulseConstraintSolver)",
        "solver-info fields the file has no slot for (`m_frictionERP`, `m_frictionCFM`, `m_restitutionVelocityThreshold`, "
        "`m_leastSquaresResidualThreshold`, ...): Bullet's defaults",
        "globals (`gContactBreakingThreshold`, `gDeactivationTime`, `gDisableDeactivation`)",
        "a hull's polyhedral features (`initializePolyhedralFeatures`) and the app's substep count and interpolation: "
        "here one fixed step per call",
        nullptr};
    return items;
}

std::string summary(const CompareResult& r)
{
    std::ostringstream o;
    if (r.exitCode == kBadInput) {
        o << "btgpu_compare: " << r.error << "\n";
        return o.str();
    }
    o << "btgpu_compare " << r.path << ": " << r.bodies << " bodies (" << r.dynamicBodies << " dynamic), "
      << r.constraints << " constraints, " << r.steps << " steps of " << g6(r.dt) << " s\n";
    o << "  device: " << (r.device.empty() ? "none" : r.device) << "; solver: " << r.solver << "; ms/step stock " << fmt("%.3f", r.stockMsPerStep)
      << ", btgpu " << fmt("%.3f", r.gpuMsPerStep) << "\n";
    if (r.gpuPathEveryStep) o << "  GPU path: every step; stages " << joined(r.gpuStages) << "\n";
    else
        o << "  GPU path: no, " << r.cpuPathSteps << " of " << r.steps << " steps on the CPU path from step "
          << r.firstCpuPathStep << ": " << r.cpuPathReason << "\n";
    const size_t last = size_t(r.steps) - 1;
    for (size_t m = 0; m < r.measures.size(); ++m) {
        const scenes::ChaosBand& b = r.bands[m][last];
        o << "  " << r.measures[m] << ": btgpu " << g6(r.gpu[m][last]) << ", stock " << g6(r.stock[m][last])
          << ", nudged stock " << g6(b.stockMean) << " +- " << g6(b.bound()) << (b.admits(r.gpu[m][last]) ? "" : "  OUTSIDE")
          << (r.judged[m] ? "" : " (not judged)") << "; outside on " << r.stepsOutside[m] << " of " << r.steps << " steps\n";
    }
    o << "  bodies outside their band at the end: " << r.bodiesOutside << " of " << r.dynamicBodies << "\n";
    for (const std::string& s : r.outside) o << "  " << s << "\n";
    o << "  verdict (exit " << r.exitCode << "): " << verdictWords(r.exitCode) << "\n";
    return o.str();
}

std::string markdown(const CompareResult& r)
{
    std::ostringstream o;
    o << "# btgpu_compare: `" << r.path << "`\n\n";
    o << "**Verdict (exit " << r.exitCode << "): " << verdictWords(r.exitCode) << ".**\n\n";
    if (r.exitCode == kBadInput) {
        o << r.error << "\n";
        return o.str();
    }
    o << "- file: Bullet " << r.file.version / 100 << "." << r.file.version % 100 << ", "
      << (r.file.doublePrecision ? "double" : "float") << ", " << (r.file.pointers64 ? "64" : "32") << "-bit pointers, "
      << r.file.chunks << " chunks\n";
    o << "- scene: " << r.bodies << " bodies (" << r.dynamicBodies << " dynamic), " << r.constraints << " constraints; "
      << "up = " << vec(r.up) << " (against gravity)\n";
    o << "- run: " << r.steps << " steps of " << g6(r.dt) << " s (`stepSimulation(dt, 1, dt)`), stock Bullet "
      << fmt("%.3f", r.stockMsPerStep) << " ms/step, btgpu " << fmt("%.3f", r.gpuMsPerStep) << " ms/step on "
      << (r.device.empty() ? "no device" : r.device) << ", solver: " << r.solver << "\n";
    if (r.gpuPathEveryStep)
        o << "- GPU path: **every step**; the plan's stages: " << joined(r.gpuStages) << "; programs built: " << joined(r.gpuPrograms)
          << "\n";
    else
        o << "- GPU path: **no** — " << r.cpuPathSteps << " of " << r.steps << " steps on the CPU path, from step "
          << r.firstCpuPathStep << ": " << r.cpuPathReason << "\n";
    o << "\nStock's chaos: stock Bullet run " << tol::kChaosRuns << " more times with every dynamic body's start moved by up to "
      << tol::kChaosNudge * 1e3 << " mm on each axis (seeds 1.." << tol::kChaosRuns << "). A value is within when it lies within "
      << tol::kChaosFactor << " × the largest distance between two nudged runs, plus the floor, of their mean "
         "(`tests/scenes/stock_chaos.h`, `tests/tolerances.h`). The unnudged stock run is one chance outcome, shown for scale.\n\n";
    o << "Judged: " << (r.everyStep ? "every step" : "the last step")
      << " (the aggregates marked judged, and every dynamic body's centre at the last step)"
      << (r.everyStep ? "" : "; `--every-step` judges the aggregates after every step") << ".\n\n";
    o << "## Aggregates at the last step\n\n| measure | judged | btgpu | stock | nudged stock mean | band ± | floor | within | steps outside | worst step (distance / band) |\n"
         "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    const size_t last = size_t(r.steps) - 1;
    for (size_t m = 0; m < r.measures.size(); ++m) {
        const scenes::ChaosBand& b = r.bands[m][last];
        size_t worst = 0;
        for (size_t s = 0; s < size_t(r.steps); ++s)
            if (r.ratio(m, s) > r.ratio(m, worst)) worst = s;
        o << "| " << r.measures[m] << " | " << (r.judged[m] ? "yes" : "no") << " | " << g6(r.gpu[m][last]) << " | " << g6(r.stock[m][last]) << " | " << g6(b.stockMean)
          << " | " << g6(b.bound()) << " | " << g6(b.floor) << " | " << (b.admits(r.gpu[m][last]) ? "yes" : "**no**") << " | "
          << r.stepsOutside[m] << " of " << r.steps << " | " << worst + 1 << " (" << fmt("%.2f", r.ratio(m, worst)) << ") |\n";
    }
    o << "\nMeasures: mean height and spread of the dynamic bodies' centres (m; spread = rms distance across `up` from "
         "their centroid), their kinetic energy (J, linear), contacts (manifolds with points: stock's dispatcher, btgpu's `Report::contacts` on the GPU path — not judged: btgpu keeps no manifold for a sleeping pair and makes one for boxes touching only at an edge or a corner, which stock's box-box detector leaves without points), at rest (fraction of dynamic "
         "bodies asleep or below their own sleeping thresholds).\n";
    if (!r.outside.empty()) {
        o << "\n";
        for (const std::string& s : r.outside) o << "- " << s << "\n";
    }
    o << "\n![divergence against time](divergence.svg)\n";
    o << "\n## Bodies at the last step\n\n" << r.bodiesOutside << " of " << r.dynamicBodies
      << " dynamic bodies are farther from the nudged runs' mean centre than " << tol::kChaosFactor
      << " × their largest stock-to-stock distance + " << tol::kChaosPositionFloor * 100
      << " cm. The farthest (all in `bodies.csv`):\n\n| body | name | btgpu centre | nudged stock mean | distance m | band m | within | speed m/s btgpu / stock | at rest btgpu / stock runs |\n"
         "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    std::vector<const BodyResult*> order;
    for (const BodyResult& b : r.finalBodies)
        if (b.dynamic) order.push_back(&b);
    std::sort(order.begin(), order.end(), [](const BodyResult* a, const BodyResult* b) {
        return a->distance / a->bound > b->distance / b->bound;
    });
    for (size_t i = 0; i < order.size() && i < 10; ++i) {
        const BodyResult& b = *order[i];
        o << "| " << b.index << " | " << b.name << " | " << vec(b.gpu) << " | " << vec(b.stockMean) << " | " << g6(b.distance)
          << " | " << g6(b.bound) << " | " << (b.within() ? "yes" : "**no**") << " | " << fmt("%.3g", b.gpuSpeed) << " / "
          << fmt("%.3g", b.stockMeanSpeed) << " | " << (b.gpuAtRest ? "yes" : "no") << " / " << fmt("%.0f%%", 100 * b.stockAtRest)
          << " |\n";
    }
    o << "\n## What the loading restored and lost\n\n";
    o << "Bullet's `btBulletWorldImporter` keeps each body's transform, shape, mass, friction, restitution and factors, "
         "recomputes the inertia from the shape and drops the rest; btgpu_compare restores from the file's records:\n\n";
    if (r.restoration.restored.empty()) o << "- nothing differed from what the importer left\n";
    for (const auto& [field, n] : r.restoration.restored) o << "- " << field << ": " << n << " bodies\n";
    o << "\nIn the file but not restorable for this scene:\n\n";
    if (r.restoration.lost.empty()) o << "- nothing\n";
    for (const auto& [field, n] : r.restoration.lost) o << "- " << field << ": " << n << " bodies\n";
    for (const std::string& s : r.restoration.notes) o << "- " << s << "\n";
    o << "\nNever in a `.bullet` file (both worlds get the same defaults):\n\n";
    for (const char* const* p = notInFile(); *p; ++p) o << "- " << *p << "\n";
    return o.str();
}

std::string timelineCsv(const CompareResult& r)
{
    std::ostringstream o;
    o << "step,time";
    for (const std::string& m : r.measures)
        o << "," << m << " btgpu," << m << " stock," << m << " nudged mean," << m << " band," << m << " divergence";
    o << "\n";
    o.precision(9);
    for (size_t s = 0; s < size_t(r.steps); ++s) {
        o << s + 1 << "," << (s + 1) * r.dt;
        for (size_t m = 0; m < r.measures.size(); ++m)
            o << "," << r.gpu[m][s] << "," << r.stock[m][s] << "," << r.bands[m][s].stockMean << "," << r.bands[m][s].bound()
              << "," << r.ratio(m, s);
        o << "\n";
    }
    return o.str();
}

std::string bodiesCsv(const CompareResult& r)
{
    std::ostringstream o;
    o.precision(9);
    o << "body,name,dynamic,btgpu x,btgpu y,btgpu z,stock x,stock y,stock z,nudged mean x,nudged mean y,nudged mean z,"
         "distance,stock chaos,band,within,btgpu speed,nudged mean speed,btgpu at rest,nudged runs at rest\n";
    for (const BodyResult& b : r.finalBodies) {
        std::string name = b.name;
        std::replace(name.begin(), name.end(), ',', ' ');
        o << b.index << "," << name << "," << (b.dynamic ? 1 : 0) << "," << b.gpu.x() << "," << b.gpu.y() << "," << b.gpu.z()
          << "," << b.stock.x() << "," << b.stock.y() << "," << b.stock.z() << "," << b.stockMean.x() << "," << b.stockMean.y()
          << "," << b.stockMean.z() << "," << b.distance << "," << b.chaos << "," << b.bound << "," << (b.within() ? 1 : 0) << "," << b.gpuSpeed
          << "," << b.stockMeanSpeed << "," << (b.gpuAtRest ? 1 : 0) << "," << b.stockAtRest << "\n";
    }
    return o.str();
}

std::string divergenceSvg(const CompareResult& r)
{
    // y: distance from the nudged mean over the band (1 = the band's edge), linear to 2 and
    // clipped there; x: simulated time.
    const double W = 760, H = 360, L = 60, R = 170, T = 30, B = 40;
    const double tEnd = r.steps * r.dt, yMax = 2.0;
    auto X = [&](double t) { return L + (W - L - R) * t / tEnd; };
    auto Y = [&](double v) { return T + (H - T - B) * (1.0 - std::min(v, yMax) / yMax); };
    std::ostringstream o;
    o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    o << "<text x=\"" << L << "\" y=\"18\" font-size=\"13\">btgpu against stock Bullet's chaos: |btgpu - nudged stock mean| / band</text>\n";
    o << "<line x1=\"" << L << "\" y1=\"" << Y(0) << "\" x2=\"" << W - R << "\" y2=\"" << Y(0) << "\" stroke=\"black\"/>\n";
    o << "<line x1=\"" << L << "\" y1=\"" << T << "\" x2=\"" << L << "\" y2=\"" << Y(0) << "\" stroke=\"black\"/>\n";
    for (double v : {0.0, 0.5, 1.0, 1.5, 2.0})
        o << "<text x=\"" << L - 6 << "\" y=\"" << Y(v) + 4 << "\" text-anchor=\"end\">" << v << (v == 2.0 ? "+" : "") << "</text>\n";
    o << "<line x1=\"" << L << "\" y1=\"" << Y(1) << "\" x2=\"" << W - R << "\" y2=\"" << Y(1)
      << "\" stroke=\"red\" stroke-dasharray=\"6,4\"/><text x=\"" << W - R - 4 << "\" y=\"" << Y(1) - 4
      << "\" text-anchor=\"end\" fill=\"red\">edge of stock's chaos</text>\n";
    for (int i = 0; i <= 4; ++i) {
        const double t = tEnd * i / 4;
        o << "<text x=\"" << X(t) << "\" y=\"" << H - B + 16 << "\" text-anchor=\"middle\">" << fmt("%.3g", t) << "</text>\n";
    }
    o << "<text x=\"" << (L + W - R) / 2 << "\" y=\"" << H - 6 << "\" text-anchor=\"middle\">simulated time (s)</text>\n";
    const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#d62728"};
    auto legend = [&](size_t i, const std::string& name, const char* dash) {
        const double y = T + 14 * double(i) + 6;
        o << "<line x1=\"" << W - R + 10 << "\" y1=\"" << y << "\" x2=\"" << W - R + 30 << "\" y2=\"" << y << "\" stroke=\""
          << colours[i % 6] << "\" stroke-width=\"2\"" << dash << "/><text x=\"" << W - R + 34 << "\" y=\"" << y + 4 << "\">"
          << name << "</text>\n";
    };
    for (size_t m = 0; m < r.measures.size(); ++m) {
        o << "<polyline fill=\"none\" stroke=\"" << colours[m % 6] << "\" stroke-width=\"1.5\" points=\"";
        for (size_t s = 0; s < size_t(r.steps); ++s) o << fmt("%.1f", X((s + 1) * r.dt)) << "," << fmt("%.1f", Y(r.ratio(m, s))) << " ";
        o << "\"/>\n";
        legend(m, r.measures[m], "");
    }
    o << "<polyline fill=\"none\" stroke=\"" << colours[5] << "\" stroke-width=\"1.5\" stroke-dasharray=\"2,2\" points=\"";
    for (size_t k = 0; k < r.worstBody.size(); ++k)
        o << fmt("%.1f", X(r.bodySampleSteps[k] * r.dt)) << "," << fmt("%.1f", Y(r.worstBody[k])) << " ";
    o << "\"/>\n";
    legend(5, "farthest body", " stroke-dasharray=\"2,2\"");
    o << "</svg>\n";
    return o.str();
}

std::string writeOutputs(const CompareResult& r, const std::string& dir)
{
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) return "cannot create " + dir + ": " + ec.message();
    const std::pair<const char*, std::string> files[] = {
        {"compare.md", markdown(r)}, {"timeline.csv", timelineCsv(r)}, {"bodies.csv", bodiesCsv(r)}, {"divergence.svg", divergenceSvg(r)}};
    for (const auto& [name, text] : files) {
        const std::string path = (std::filesystem::path(dir) / name).string();
        std::ofstream f(path, std::ios::binary);
        f << text;
        f.close();
        if (!f) return "cannot write " + path;
    }
    return "";
}

}  // namespace btgpu::compare
