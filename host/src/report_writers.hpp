// scatterlut generator — `report`'s writers: CSV and SVG per ladder, the Markdown section of
// one table (report.cpp writes report.md around them).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "report_gpu.hpp"
#include "report_ladders.hpp"
#include "svg_plot.hpp"

namespace scatterlut {

// Writes `text` to `path` atomically.
void write_text(const std::string &path, const std::string &text);

std::string tolerance_csv(const std::vector<ToleranceRung> &rungs);
std::string resolution_csv(const std::vector<ResolutionRung> &rungs);
std::string methods_csv(const std::vector<MethodRow> &rows);

Plot tolerance_plot(const std::string &kind, const std::vector<ToleranceRung> &rungs);
Plot resolution_plot(const std::string &kind, const std::vector<ResolutionRung> &rungs, double accepted);
Plot methods_plot(const std::string &kind, const std::vector<MethodRow> &rows, double accepted);

// The Markdown section of one table: its requests and plan, then the three ladders with the
// names of their SVG files (<kind>_tolerance.svg, …).
std::string markdown_section(const PlannedTable &t, Storage storage, const RadianceQueries &qs,
                             const std::vector<ToleranceRung> &tol, const std::vector<ResolutionRung> &res,
                             const std::vector<MethodRow> &methods);

// ---- The GPU section (report_gpu_writers.cpp): per group of tables one snippet samples, the
// CPU methods and the GPU rows side by side (<first table>_gpu.csv, <first table>_gpu.svg).

// The group's files' stem: its first table's name and "_gpu".
std::string gpu_stem(const GpuGroup &g);
// The CPU methods of the group's tables in one list (`by_table`: each table's runtime methods):
// the reference (exact) once, a name followed by its table's where the group has several.
std::vector<MethodRow> group_cpu_methods(const GpuGroup &g, const std::map<std::string, std::vector<MethodRow>> &by_table);
// side (cpu / gpu), method, tier, table, ns (CPU: per call; GPU: per pixel net of the inputs),
// the GPU's whole frame per pixel and its per-round ratio to the baseline, errors, queries.
std::string gpu_csv(const GpuGroup &g, const std::vector<MethodRow> &cpu);
// Error against cost: the CPU methods (filled markers) and the GPU rows (rings, dashed), the
// Pareto front of the GPU rows' max errors, the scene's accepted error.
Plot gpu_plot(const GpuGroup &g, const std::vector<MethodRow> &cpu, double accepted);
// The section "On the GPU: the snippets' tiers" of report.md (cpu[i]: group i's CPU methods).
std::string gpu_markdown(const GpuSection &s, const std::vector<std::vector<MethodRow>> &cpu, double accepted);

} // namespace scatterlut
