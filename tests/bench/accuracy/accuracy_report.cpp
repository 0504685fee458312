// accuracy_report.cpp — CSV, SVG plots (written by hand: no plotting dependency) and the
// Markdown summary of btgpu_accuracy.
#include "accuracy_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace btgpu::accuracy {

namespace {

bool usable(const RunResult& r) { return r.ran && r.finite && std::isfinite(r.measurement.error) && r.msPerSimS > 0; }

const char* colour(const std::string& engine) { return engine == "stock" ? "#1f77b4" : "#d62728"; }

std::string num(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

std::string xmlEscape(const std::string& s)
{
    std::string o;
    for (char ch : s) {
        if (ch == '&') o += "&amp;";
        else if (ch == '<') o += "&lt;";
        else if (ch == '>') o += "&gt;";
        else o += ch;
    }
    return o;
}

}  // namespace

std::string settingLabel(const Setting& s)
{
    return s.solver + " i" + std::to_string(s.iterations) + " s" + std::to_string(s.substeps);
}

std::vector<std::size_t> paretoFront(const std::vector<RunResult>& runs, const std::string& engine)
{
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < runs.size(); ++i)
        if (runs[i].engine == engine && usable(runs[i])) idx.push_back(i);
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
        if (runs[a].msPerSimS != runs[b].msPerSimS) return runs[a].msPerSimS < runs[b].msPerSimS;
        return runs[a].measurement.error < runs[b].measurement.error;
    });
    std::vector<std::size_t> front;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i : idx)
        if (runs[i].measurement.error < best) {
            best = runs[i].measurement.error;
            front.push_back(i);
        }
    return front;
}

void writeCsv(std::ostream& out, const std::vector<RunResult>& runs)
{
    out << "scene,engine,solver,iterations,substeps,copies,bodies,sim_s,wall_ms,ms_per_sim_s,error,"
           "max_penetration_m,finite,device,notes\n";
    for (const RunResult& r : runs) {
        // A setting an engine does not have (stock's soft step) has no row: its zeros would plot as
        // a perfect run. stderr names it.
        if (!r.ran) continue;
        out << r.scene << ',' << r.engine << ',' << r.setting.solver << ',' << r.setting.iterations << ','
            << r.setting.substeps << ',' << r.copies << ',' << r.bodies << ',' << num(r.simSeconds) << ','
            << num(r.wallMs) << ',' << num(r.msPerSimS) << ',' << num(r.measurement.error) << ','
            << num(r.measurement.penetration) << ',' << (r.finite ? 1 : 0) << ",\"" << r.device << "\",\""
            << r.measurement.notes << "\"\n";
    }
}

void writeSvg(std::ostream& out, const Case& c, const std::vector<RunResult>& runs)
{
    const double W = 760, H = 500, L = 90, R = 150, T = 50, B = 60;
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    // A zero error cannot go on a log axis: it is drawn at the floor (and the CSV keeps 0).
    double floorErr = 1e300;
    for (const RunResult& r : runs)
        if (usable(r) && r.measurement.error > 0) floorErr = std::min(floorErr, r.measurement.error);
    floorErr = floorErr < 1e300 ? floorErr / 2 : 1e-9;
    auto errOf = [&](const RunResult& r) { return std::max(r.measurement.error, floorErr); };
    for (const RunResult& r : runs)
        if (usable(r)) {
            xmin = std::min(xmin, r.msPerSimS), xmax = std::max(xmax, r.msPerSimS);
            ymin = std::min(ymin, errOf(r)), ymax = std::max(ymax, errOf(r));
        }
    if (xmin > xmax) xmin = 1, xmax = 10, ymin = 1e-3, ymax = 1;
    const double lx0 = std::floor(std::log10(xmin)), lx1 = std::max(lx0 + 1, std::ceil(std::log10(xmax)));
    const double ly0 = std::floor(std::log10(ymin)), ly1 = std::max(ly0 + 1, std::ceil(std::log10(ymax)));
    auto px = [&](double v) { return L + (std::log10(v) - lx0) / (lx1 - lx0) * (W - L - R); };
    auto py = [&](double v) { return H - B - (std::log10(v) - ly0) / (ly1 - ly0) * (H - T - B); };

    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    out << "<text x=\"" << L << "\" y=\"20\" font-size=\"14\" font-weight=\"bold\">" << xmlEscape(c.name) << ": "
        << xmlEscape(c.description) << "</text>\n";
    std::string device;
    for (const RunResult& r : runs)
        if (r.engine == "btgpu" && !r.device.empty()) device = r.device;
    if (device.size() > 48) device = device.substr(0, 45) + "...";
    out << "<text x=\"" << L << "\" y=\"38\" font-size=\"10\" fill=\"#555\">btgpu on " << xmlEscape(device)
        << "; stock: float Bullet, CPU; labels: iterations (i), substeps (s)</text>\n";
    // Grid and ticks: decades labelled, 2..9 as minor ticks.
    for (int d = int(lx0); d <= int(lx1); ++d)
        for (int m = 1; m <= (d < int(lx1) ? 9 : 1); ++m) {
            const double x = px(m * std::pow(10.0, d));
            out << "<line x1=\"" << x << "\" y1=\"" << T << "\" x2=\"" << x << "\" y2=\"" << H - B << "\" stroke=\""
                << (m == 1 ? "#ccc" : "#eee") << "\"/>\n";
            if (m == 1)
                out << "<text x=\"" << x << "\" y=\"" << H - B + 16 << "\" text-anchor=\"middle\">"
                    << num(std::pow(10.0, d)) << "</text>\n";
        }
    for (int d = int(ly0); d <= int(ly1); ++d)
        for (int m = 1; m <= (d < int(ly1) ? 9 : 1); ++m) {
            const double y = py(m * std::pow(10.0, d));
            out << "<line x1=\"" << L << "\" y1=\"" << y << "\" x2=\"" << W - R << "\" y2=\"" << y << "\" stroke=\""
                << (m == 1 ? "#ccc" : "#eee") << "\"/>\n";
            if (m == 1)
                out << "<text x=\"" << L - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">"
                    << num(std::pow(10.0, d)) << "</text>\n";
        }
    out << "<rect x=\"" << L << "\" y=\"" << T << "\" width=\"" << W - L - R << "\" height=\"" << H - T - B
        << "\" fill=\"none\" stroke=\"black\"/>\n";
    out << "<text x=\"" << (L + W - R) / 2 << "\" y=\"" << H - 18
        << "\" text-anchor=\"middle\">run time (ms of wall clock per simulated second)</text>\n";
    out << "<text transform=\"translate(22," << (T + H - B) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
        << xmlEscape(c.errorLabel) << "</text>\n";

    int legend = 0;
    for (const std::string engine : {"stock", "btgpu"}) {
        const char* col = colour(engine);
        const std::vector<std::size_t> front = paretoFront(runs, engine);
        std::string pts;
        for (std::size_t i : front) pts += num(px(runs[i].msPerSimS)) + "," + num(py(errOf(runs[i]))) + " ";
        out << "<polyline points=\"" << pts << "\" fill=\"none\" stroke=\"" << col << "\" stroke-width=\"2\"/>\n";
        for (std::size_t i = 0; i < runs.size(); ++i) {
            const RunResult& r = runs[i];
            if (r.engine != engine || !usable(r)) continue;
            const bool onFront = std::find(front.begin(), front.end(), i) != front.end();
            const double x = px(r.msPerSimS), y = py(errOf(r));
            out << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"4\" stroke=\"" << col << "\" fill=\""
                << (onFront ? col : "white") << "\"><title>" << engine << ' ' << settingLabel(r.setting) << ": "
                << num(r.msPerSimS) << " ms/s, error " << num(r.measurement.error) << "</title></circle>\n";
            if (onFront)
                out << "<text x=\"" << x + 6 << "\" y=\"" << y - 6 << "\" font-size=\"10\" fill=\"" << col << "\">i"
                    << r.setting.iterations << " s" << r.setting.substeps << "</text>\n";
        }
        const double ly = T + 10 + 36 * legend++;
        out << "<circle cx=\"" << W - R + 16 << "\" cy=\"" << ly << "\" r=\"4\" fill=\"" << col << "\"/>"
            << "<text x=\"" << W - R + 26 << "\" y=\"" << ly + 4 << "\">" << engine << " (front)</text>\n"
            << "<circle cx=\"" << W - R + 16 << "\" cy=\"" << ly + 16 << "\" r=\"4\" fill=\"white\" stroke=\"" << col
            << "\"/><text x=\"" << W - R + 26 << "\" y=\"" << ly + 20 << "\">" << engine << " (other)</text>\n";
    }
    out << "</svg>\n";
}

void writeMarkdown(std::ostream& out, const std::vector<Case>& cases, const std::vector<RunResult>& runs)
{
    out << "# btgpu_accuracy summary\n\nError against run time (ms of wall clock per simulated second). For "
           "each scene, the most accurate setting of each engine that fits a time budget.\n";
    for (const Case& c : cases) {
        std::vector<RunResult> mine;
        for (const RunResult& r : runs)
            if (r.scene == c.name) mine.push_back(r);
        double lo = 1e300, hi = 0;
        for (const RunResult& r : mine)
            if (usable(r)) lo = std::min(lo, r.msPerSimS), hi = std::max(hi, r.msPerSimS);
        if (mine.empty()) continue;
        out << "\n## " << c.name << " — " << c.description << "\n\nerror: " << c.errorLabel << "\n\n";
        if (hi <= 0) {
            out << "no usable runs\n";
            continue;
        }
        out << "| budget (ms/sim s) | stock: setting | stock: error | btgpu: setting | btgpu: error |\n"
               "| ---: | --- | ---: | --- | ---: |\n";
        for (int k = 0; k < 4; ++k) {
            const double budget = lo * std::pow(hi / lo, k / 3.0) * (1 + 1e-9);
            out << "| " << num(budget);
            for (const std::string engine : {"stock", "btgpu"}) {
                const RunResult* best = nullptr;
                for (const RunResult& r : mine)
                    if (r.engine == engine && usable(r) && r.msPerSimS <= budget &&
                        (!best || r.measurement.error < best->measurement.error))
                        best = &r;
                if (best) out << " | " << settingLabel(best->setting) << " | " << num(best->measurement.error);
                else out << " | — | —";
            }
            out << " |\n";
        }
        for (const RunResult& r : mine)
            if (r.ran && !r.finite) out << "\n**" << r.engine << ' ' << settingLabel(r.setting) << ": non-finite state**\n";
    }
}

}  // namespace btgpu::accuracy
