// compare_report.h — btgpu_compare's outputs: a Markdown report, CSVs (the aggregates per step
// with their stock bands, and each body's final centre against its band) and an SVG of the
// divergence against time (distance from the stock mean over the band's half-width).
#pragma once
#include <string>

#include "compare/compare_run.h"

namespace btgpu::compare {

// What a .bullet file cannot carry, so no loader can restore it (listed in every report).
const char* const* notInFile();

std::string markdown(const CompareResult& r);
std::string timelineCsv(const CompareResult& r);
std::string bodiesCsv(const CompareResult& r);
std::string divergenceSvg(const CompareResult& r);
// A few lines for the terminal.
std::string summary(const CompareResult& r);
// Writes compare.md, timeline.csv, bodies.csv and divergence.svg into `dir` (created if
// missing); "" on success, else what failed.
std::string writeOutputs(const CompareResult& r, const std::string& dir);

}  // namespace btgpu::compare
