// bench_report.cpp — Markdown and CSV output of bench results (see bench_report.h).
#include "bench_report.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace btgpu::bench {

namespace {

std::string num(double v, const char* fmt = "%.2f")
{
    if (v < 0) return "n/a";
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}
std::string signedNum(double v, const char* fmt)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}
std::string count(long v) { return v < 0 ? "n/a" : std::to_string(v); }
std::string mb(long long bytes) { return bytes < 0 ? "n/a" : num(bytes / 1048576.0, "%.1f"); }

const RunResult* bullet(const std::vector<RunResult>& results)
{
    for (const RunResult& r : results)
        if (r.backend == "bullet" && r.ran) return &r;
    return nullptr;
}

std::string csvQuote(std::string s)
{
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace

void writeMarkdown(std::ostream& out, const Scene& scene, int frames, const std::vector<RunResult>& results)
{
    out << "## btgpu_bench: " << scene.name << " (" << scene.dynamicCount() << " dynamic, "
        << scene.bodies.size() - scene.dynamicCount() << " static), frames 1.." << frames << ", dt 1/"
        << int(1 / scene.dt + 0.5f) << ", " << scene.iterations << " iterations\n\n";
    out << "| backend | device | frames | step ms med / p90 / max | write-back ms med / p90 / max | total ms med | "
           "vs bullet | set-up s / first step s | pairs | manifolds | points | device MB | lowest y (frame) | final lowest y | NaN | below ground |\n";
    out << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    const RunResult* base = bullet(results);
    for (const RunResult& r : results) {
        if (!r.ran) {
            out << "| " << r.backend << " | " << (r.device.empty() ? "-" : r.device) << " | skipped: " << r.skipped
                << " ||||||||||||||\n";
            continue;
        }
        std::string speed = base && r.totalMs.median > 0 ? num(base->totalMs.median / r.totalMs.median, "%.2fx") : "-";
        out << "| " << r.backend << " | " << r.device << " | " << r.framesRun << (r.cutShort ? " (cut: budget)" : "")
            << " | " << num(r.stepMs.median) << " / " << num(r.stepMs.p90) << " / " << num(r.stepMs.max) << " | "
            << num(r.writebackMs.median) << " / " << num(r.writebackMs.p90) << " / " << num(r.writebackMs.max)
            << " | " << num(r.totalMs.median) << " | " << speed << " | " << num(r.setUpS, "%.2f") << " / "
            << num(r.firstStepS, "%.2f") << " | "
            << count(r.last.pairs) << " | " << count(r.last.manifolds) << " | " << count(r.last.points) << " | "
            << mb(r.last.deviceBytes) << " | " << signedNum(r.minLowestY, "%.3f") << " (" << r.minLowestFrame << ") | "
            << signedNum(r.finalLowestY, "%.3f") << " | "
            << r.nanBodies << " | " << r.belowGround << " |\n";
    }
    out << "\nLowest y: the lowest point of any dynamic body over the run (ground top y = 0; below 0 = "
           "penetration), over the run and after the last frame. Counts are after the last frame.\n";
    for (const RunResult& r : results) {
        out << "\n**" << r.backend << "**: " << (r.notes.empty() ? std::string("-") : r.notes);
        if (!r.last.overflow.empty()) out << "; OVERFLOW: " << r.last.overflow;
        out << "\n";
    }
    for (const RunResult& r : results) {
        if (r.stageMedianMs.empty()) continue;
        std::vector<std::pair<std::string, double>> stages(r.stageMedianMs.begin(), r.stageMedianMs.end());
        std::sort(stages.begin(), stages.end(), [](auto& a, auto& b) { return a.second > b.second; });
        out << "\n| " << r.backend << " stage | median ms |\n|---|---|\n";
        for (auto& [name, ms] : stages) out << "| " << name << " | " << num(ms, "%.3f") << " |\n";
    }
}

void writeCsv(std::ostream& out, const Scene& scene, const std::vector<RunResult>& results)
{
    out << "scene,dynamic,backend,device,ran,skipped,frames,cut_short,step_med_ms,step_p90_ms,step_max_ms,"
           "writeback_med_ms,writeback_p90_ms,writeback_max_ms,total_med_ms,total_p90_ms,total_max_ms,set_up_s,first_step_s,"
           "pairs,manifolds,points,device_bytes,lowest_y,lowest_y_frame,final_lowest_y,nan_bodies,below_ground,overflow,stages,notes\n";
    for (const RunResult& r : results) {
        std::string stages;
        for (auto& [name, ms] : r.stageMedianMs) stages += (stages.empty() ? "" : ";") + name + "=" + num(ms, "%.4f");
        out << csvQuote(scene.name) << ',' << scene.dynamicCount() << ',' << r.backend << ',' << csvQuote(r.device)
            << ',' << r.ran << ',' << csvQuote(r.skipped) << ',' << r.framesRun << ',' << r.cutShort << ','
            << num(r.stepMs.median, "%.4f") << ',' << num(r.stepMs.p90, "%.4f") << ',' << num(r.stepMs.max, "%.4f")
            << ',' << num(r.writebackMs.median, "%.4f") << ',' << num(r.writebackMs.p90, "%.4f") << ','
            << num(r.writebackMs.max, "%.4f") << ',' << num(r.totalMs.median, "%.4f") << ','
            << num(r.totalMs.p90, "%.4f") << ',' << num(r.totalMs.max, "%.4f") << ',' << num(r.setUpS, "%.3f")
            << ',' << num(r.firstStepS, "%.3f")
            << ',' << r.last.pairs << ',' << r.last.manifolds << ',' << r.last.points << ',' << r.last.deviceBytes
            << ',' << (r.ran ? signedNum(r.minLowestY, "%.4f") : "") << ',' << r.minLowestFrame << ','
            << (r.ran ? signedNum(r.finalLowestY, "%.4f") : "") << ',' << r.nanBodies << ','
            << r.belowGround << ',' << csvQuote(r.last.overflow) << ',' << csvQuote(stages) << ','
            << csvQuote(r.notes) << '\n';
    }
}

}  // namespace btgpu::bench
