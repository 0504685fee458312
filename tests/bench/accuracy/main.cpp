// main.cpp — btgpu_accuracy: error against run time on btgpu and stock Bullet (float) for the
// reference scenes, sweeping solver kind, iterations and substeps. Writes accuracy.csv and one
// SVG per scene under --out, a Markdown summary on stdout, progress on stderr.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "accuracy_report.h"

using namespace btgpu::accuracy;

namespace {

const char* kUsage =
    "usage: btgpu_accuracy [--quick] [--scene NAME[,NAME...]] [--out DIR] [--device NAME]\n"
    "                      [--solvers pgs,jacobi,soft] [--iterations 1,2,4,8,16,32] [--substeps 1,2,4,8]\n"
    "                      [--copies 1000] [--engines stock,btgpu] [--reference FILE] [--list]\n"
    "  --quick: iterations 2,10, substeps 1,2, 100 copies, shorter runs (the ctest run).\n"
    "  --reference: btgpu_accuracy_reference's file for the pile (default DIR/pile_reference.csv).\n"
    "  BTGPU_DEVICE=gpu|cpu|<name substring> picks btgpu's OpenCL device (overrides --device).\n";

[[noreturn]] void usage(const std::string& why)
{
    std::fprintf(stderr, "btgpu_accuracy: %s\n%s", why.c_str(), kUsage);
    std::exit(2);
}

std::vector<std::string> split(const std::string& s)
{
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

std::vector<int> ints(const std::string& s)
{
    std::vector<int> out;
    for (const std::string& item : split(s)) {
        const int v = std::atoi(item.c_str());
        if (v < 1) usage("counts must be positive: " + s);
        out.push_back(v);
    }
    return out;
}

}  // namespace

int main(int argc, char** argv)
{
    bool quick = false, list = false;
    std::string outDir = "accuracy_out", scenesArg, referencePath, solvers = "pgs", engines = "stock,btgpu";
    std::string iterationsArg, substepsArg;
    int copies = 0;
    btgpu::Config config;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> const char* {
            if (i + 1 >= argc) usage("missing value after " + a);
            return argv[++i];
        };
        if (a == "--quick") quick = true;
        else if (a == "--scene") scenesArg = next();
        else if (a == "--out") outDir = next();
        else if (a == "--device") config.device = next();
        else if (a == "--solvers") solvers = next();
        else if (a == "--iterations") iterationsArg = next();
        else if (a == "--substeps") substepsArg = next();
        else if (a == "--copies") copies = std::atoi(next());
        else if (a == "--engines") engines = next();
        else if (a == "--reference") referencePath = next();
        else if (a == "--list") list = true;
        else if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else usage("unknown argument " + a);
    }
    const std::vector<int> iterations = ints(iterationsArg.empty() ? (quick ? "2,10" : "1,2,4,8,16,32") : iterationsArg);
    const std::vector<int> substeps = ints(substepsArg.empty() ? (quick ? "1,2" : "1,2,4,8") : substepsArg);
    if (copies <= 0) copies = quick ? 100 : 1000;
    for (const std::string& e : split(engines))
        if (e != "stock" && e != "btgpu") usage("engines are stock and btgpu");
    for (const std::string& k : split(solvers))
        if (!solverKindSupported("stock", k) && !solverKindSupported("btgpu", k)) usage("unknown solver kind " + k);

    std::filesystem::create_directories(outDir);
    if (referencePath.empty()) referencePath = (std::filesystem::path(outDir) / "pile_reference.csv").string();
    PileReference pile;
    std::string why;
    if (!readPileReference(referencePath, pile, why))
        std::fprintf(stderr, "btgpu_accuracy: pile: %s; its error is left empty (run btgpu_accuracy_reference)\n",
                     why.c_str());

    std::vector<Case> cases = makeCases(quick, pile);
    if (list) {
        for (const Case& c : cases) std::printf("%-16s %s\n", c.name.c_str(), c.description.c_str());
        return 0;
    }
    if (!scenesArg.empty()) {
        std::vector<Case> chosen;
        for (const std::string& name : split(scenesArg)) {
            auto it = std::find_if(cases.begin(), cases.end(), [&](const Case& c) { return c.name == name; });
            if (it == cases.end()) usage("unknown scene " + name + " (--list shows them)");
            chosen.push_back(*it);
        }
        cases = chosen;
    }

    std::vector<RunResult> runs;
    int failures = 0;
    for (const Case& c : cases) {
        std::vector<RunResult> mine;
        for (const std::string& solver : split(solvers))
            for (int it : iterations)
                for (int sub : substeps)
                    for (const std::string& engine : split(engines)) {
                        const Setting s{solver, it, sub};
                        RunResult r = runCase(c, engine, s, copies, config);
                        if (r.ran)
                            std::fprintf(stderr, "%-16s %-6s %-14s %6d bodies %10.1f ms/sim s  error %.4g %s\n",
                                         c.name.c_str(), engine.c_str(), settingLabel(s).c_str(), r.bodies,
                                         r.msPerSimS, r.measurement.error, r.finite ? "" : "NON-FINITE");
                        else
                            std::fprintf(stderr, "%-16s %-6s %-14s skipped: %s\n", c.name.c_str(), engine.c_str(),
                                         settingLabel(s).c_str(), r.skipped.c_str());
                        if (r.ran && !r.finite) ++failures;
                        mine.push_back(r);
                    }
        std::ofstream svg(std::filesystem::path(outDir) / (c.name + ".svg"));
        writeSvg(svg, c, mine);
        if (!svg) ++failures;
        runs.insert(runs.end(), mine.begin(), mine.end());
    }
    std::ofstream csv(std::filesystem::path(outDir) / "accuracy.csv");
    writeCsv(csv, runs);
    if (!csv) ++failures;
    writeMarkdown(std::cout, cases, runs);
    return failures ? 1 : 0;
}
