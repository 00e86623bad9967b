// scatterlut generator — `report`'s writers: CSV and SVG per ladder, the Markdown section of
// one table (report.cpp writes report.md around them).
#pragma once

#include <string>
#include <vector>

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

} // namespace scatterlut
