// bench_report.h — writes the run results: a Markdown table (plus per-stage tables and the
// settings each backend ran with) for stdout, and one CSV row per backend.
#pragma once
#include <ostream>
#include <vector>

#include "bench_run.h"

namespace btgpu::bench {

void writeMarkdown(std::ostream& out, const Scene& scene, int frames, const std::vector<RunResult>& results);
void writeCsv(std::ostream& out, const Scene& scene, const std::vector<RunResult>& results);

}  // namespace btgpu::bench
