// accuracy_report.h — what btgpu_accuracy writes: the CSV of every run, one SVG per scene
// (log-log error against run time, both engines, each engine's Pareto front joined) and a
// Markdown summary (per scene, the best setting of each engine within a few time budgets).
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "accuracy_run.h"

namespace btgpu::accuracy {

// Indices into runs of one scene and engine that no other run beats in both time and error,
// fastest first.
std::vector<std::size_t> paretoFront(const std::vector<RunResult>& runs, const std::string& engine);

void writeCsv(std::ostream& out, const std::vector<RunResult>& runs);
// runs: one scene's; errorLabel: the y axis.
void writeSvg(std::ostream& out, const Case& c, const std::vector<RunResult>& runs);
void writeMarkdown(std::ostream& out, const std::vector<Case>& cases, const std::vector<RunResult>& runs);

std::string settingLabel(const Setting& s);  // "pgs i8 s2"

}  // namespace btgpu::accuracy
