// `report`'s GPU section as CSV, SVG and Markdown (report_writers.hpp; the measurement:
// report_gpu.cpp).
#include <cmath>
#include <string>
#include <utility>

#include "report_writers.hpp"
#include "text_format.hpp"

namespace scatterlut {

namespace {

std::string tables_text(const GpuGroup &g) {
    std::string s;
    for (const std::string &t : g.tables) s += (s.empty() ? "" : ", ") + t;
    return s;
}

// "**Not measured:** why." in Markdown: a reason of several lines (a compiler's log) in a block.
std::string not_measured(const std::string &why) {
    const size_t eol = why.find('\n');
    if (eol == std::string::npos) return "**Not measured:** " + why + ".\n";
    return "**Not measured:** " + why.substr(0, eol) + "\n\n```text\n" + why.substr(eol + 1) +
           (why.back() == '\n' ? "" : "\n") + "```\n";
}

// A figure of the GPU's cost; "-" where there is none.
std::string or_dash(bool have, const std::string &text) { return have ? text : std::string("-"); }

} // namespace

std::string gpu_stem(const GpuGroup &g) { return g.tables.front() + "_gpu"; }

std::vector<MethodRow> group_cpu_methods(const GpuGroup &g,
                                         const std::map<std::string, std::vector<MethodRow>> &by_table) {
    std::vector<MethodRow> out;
    bool have_reference = false;
    for (const std::string &t : g.tables) {
        const auto it = by_table.find(t);
        if (it == by_table.end()) continue;
        for (MethodRow r : it->second) {
            if (r.reference) {
                if (have_reference) continue;
                have_reference = true;
            } else if (g.tables.size() > 1) {
                r.name += " (" + t + ")";
            }
            out.push_back(r);
        }
    }
    return out;
}

std::string gpu_csv(const GpuGroup &g, const std::vector<MethodRow> &cpu) {
    std::string s = "side,method,tier,table,ns,ns_per_pixel_frame,ratio_to_baseline,ratio_min,ratio_max,median_rel,"
                    "p90_rel,p99_rel,max_rel,queries\n";
    for (const MethodRow &r : cpu) {
        auto e = [&](double v) { return r.reference ? std::string("reference") : fmt("%.6g", v); };
        s += "cpu," + r.name + ",-,-," + fmt("%.5g", r.ns_per_call) + ",-,-,-,-," + e(r.error.median) + "," +
             e(r.error.p90) + "," + e(r.error.p99) + "," + e(r.error.max) + "," + std::to_string(r.error.points) + "\n";
    }
    for (const GpuRow &r : g.rows)
        s += "gpu," + r.name + "," + or_dash(!r.tier.empty(), r.tier) + "," + or_dash(!r.table.empty(), r.table) + "," +
             fmt("%.5g", r.ns_per_pixel) + "," + fmt("%.5g", r.ns_per_pixel_gross) + "," + fmt("%.4g", r.ratio) + "," +
             fmt("%.4g", r.ratio_min) + "," + fmt("%.4g", r.ratio_max) + "," + fmt("%.6g", r.error.median) + "," +
             fmt("%.6g", r.error.p90) + "," + fmt("%.6g", r.error.p99) + "," + fmt("%.6g", r.error.max) + "," +
             std::to_string(r.error.points) + "\n";
    return s;
}

Plot gpu_plot(const GpuGroup &g, const std::vector<MethodRow> &cpu, double accepted) {
    Plot p;
    p.title = tables_text(g) + ": CPU methods and GPU tiers (" + g.snippet + ")";
    p.x_label = "ns per radiance: CPU per call; GPU per pixel, net of reading the inputs";
    p.y_label = "relative error vs exact (median, p99, max)";
    p.log_x = p.log_y = true;
    for (const MethodRow &r : cpu) {
        if (r.reference) {
            p.vlines.push_back({r.ns_per_call, "CPU exact (the reference) " + fmt("%.3g", r.ns_per_call) + " ns"});
            continue;
        }
        PlotSeries s;
        s.label = "CPU " + r.name;
        s.points = {{r.ns_per_call, r.error.median}, {r.ns_per_call, r.error.p99}, {r.ns_per_call, r.error.max}};
        s.point_labels = {"median", "p99", "max"};
        if (r.name.rfind("table", 0) == 0) p.markers.push_back({{r.ns_per_call, r.error.max}, "planned " + r.name});
        p.series.push_back(s);
    }
    std::vector<PlotPoint> gpu_max;
    for (const GpuRow &r : g.rows) {
        PlotSeries s;
        s.label = "GPU " + r.name;
        s.points = {{r.ns_per_pixel, r.error.median}, {r.ns_per_pixel, r.error.p99}, {r.ns_per_pixel, r.error.max}};
        s.point_labels = {"median", "p99", "max"};
        s.hollow = s.dashed = true;
        gpu_max.push_back({r.ns_per_pixel, r.error.max});
        p.series.push_back(s);
    }
    if (!g.rows.empty()) {
        PlotSeries front;
        front.label = "GPU Pareto front (max)";
        front.points = pareto_front(gpu_max);
        front.dashed = true;
        p.series.push_back(front);
    }
    p.hlines.push_back({accepted, "accepted error " + fmt("%.3g", accepted)});
    return p;
}

std::string gpu_markdown(const GpuSection &s, const std::vector<std::vector<MethodRow>> &cpu, double accepted) {
    std::string md = "\n## On the GPU: the snippets' tiers\n\n";
    md += "Every planned table that a GLSL snippet samples (docs/SHADERS.md), in each tier the snippet runs it in "
          "(`SLUT_TIER_FAST`, `SLUT_TIER_ACCURATE`, none) and beside the per-pixel forms engines use instead, drawn "
          "through OpenGL as a fragment pass over the table's own radiance queries above (one query per pixel) with "
          "the generated snippet embedded in this scatterlut; the float radiance read back is compared with the same "
          "exact references as the CPU methods.";
    if (!s.measured) {
        md += "\n\n" + not_measured(s.why_not) + "\n";
        if (!s.groups.empty()) {
            md += "It would draw:\n\n";
            for (const GpuGroup &g : s.groups) md += "- " + tables_text(g) + " (" + g.snippet + ")\n";
        }
        return md;
    }
    md += " Cost: ns per pixel net of a pass that only reads the inputs (median frame of " +
          std::to_string(s.options.rounds) + " interleaved rounds of " + std::to_string(s.options.frames) +
          " frames each), and each frame's ratio to the group's baseline frame in the same round (median [min-max] of "
          "the rounds; a net figure near 0, or below, is within the noise of the inputs pass); the whole GPU "
          "measurement took " +
          fmt("%.1f", s.seconds) + " s.\n\n";
    md += "Renderer: " + s.renderer +
          ". **These GPU ns are llvmpipe, Mesa's rasterizer, on this machine's CPU: a "
          "relative measure between the GPU rows (and beside the CPU's ns per call, which are one C++ call each on "
          "the same CPU), not the cost on a GPU.** The error of the fast tier on llvmpipe is the accurate tier's: "
          "llvmpipe filters R32F with float weights, where most GPUs use 8-bit ones (docs/SHADERS.md, \"Options\"). "
          "The chart's Pareto front joins the GPU rows only: CPU and GPU costs are different units.\n";
    for (size_t i = 0; i < s.groups.size(); ++i) {
        const GpuGroup &g = s.groups[i];
        md += "\n### " + tables_text(g) + " (`" + g.snippet + "`)\n\n";
        if (!g.why_not.empty()) {
            md += not_measured(g.why_not);
            continue;
        }
        md += "![CPU methods and GPU tiers](" + gpu_stem(g) + ".svg)\n\n";
        md += "- " + std::to_string(g.queries) + " queries drawn as a " + std::to_string(g.width) + " x " +
              std::to_string(g.height) + " frame (each query on " +
              fmt("%.3g", static_cast<double>(g.width) * g.height / static_cast<double>(g.queries)) +
              " pixels); errors on the first drawing of each\n";
        for (const std::string &n : g.notes) md += "- note: " + n + "\n";
        md += "\n| side | method | what | ns | / " + g.baseline +
              " per frame | median | p99 | max |\n"
              "|---|---|---|---:|---:|---:|---:|---:|\n";
        for (const MethodRow &r : cpu[i]) {
            auto e = [&](double v) { return r.reference ? std::string("reference") : fmt("%.2e", v); };
            md += "| CPU | " + r.name + " | " + r.what + " | " + fmt("%.4g", r.ns_per_call) + " per call | | " +
                  e(r.error.median) + " | " + e(r.error.p99) + " | " + e(r.error.max) + " |\n";
        }
        for (const GpuRow &r : g.rows)
            md += "| GPU | " + r.name + " | " + r.what + (r.table.empty() ? "" : "; samples " + r.table) + " | " +
                  fmt("%.3g", r.ns_per_pixel) + " per pixel | " + fmt("%.2f", r.ratio) + " [" +
                  fmt("%.2f", r.ratio_min) + "-" + fmt("%.2f", r.ratio_max) + "] | " + fmt("%.2e", r.error.median) +
                  " | " + fmt("%.2e", r.error.p99) + " | " + fmt("%.2e", r.error.max) + " |\n";
    }
    md += "\nThe scene's accepted error is " + fmt("%.3g", accepted) + ".\n";
    return md;
}

} // namespace scatterlut
