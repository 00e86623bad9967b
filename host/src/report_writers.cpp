#include "report_writers.hpp"

#include <cstdint>
#include <string>
#include <utility>

#include "text_format.hpp"
#include "scatterlut/io.hpp"

namespace scatterlut {

void write_text(const std::string &path, const std::string &text) {
    write_file_atomic(path, std::vector<uint8_t>(text.begin(), text.end()));
}

std::string tolerance_csv(const std::vector<ToleranceRung> &rungs) {
    std::string s = "tolerance,generation_ms_median,max_node_rel_error,planned\n";
    for (const auto &r : rungs)
        s += fmt("%.3g", r.tolerance) + "," + fmt("%.6g", r.median_ms) + "," + fmt("%.6g", r.max_node_rel) + "," +
             (r.planned ? "1" : "0") + "\n";
    return s;
}

std::string resolution_csv(const std::vector<ResolutionRung> &rungs) {
    std::string s = "counts,storage,bytes,table_max_rel,radiance_max_rel,radiance_p99_rel,radiance_median_rel,"
                    "queries,ns_per_lookup,planned\n";
    for (const auto &r : rungs)
        s += counts_text(r.counts) + "," + to_string(r.storage) + "," + std::to_string(r.bytes) + "," +
             fmt("%.6g", r.table_max_rel) + "," + fmt("%.6g", r.radiance.max) + "," + fmt("%.6g", r.radiance.p99) + "," +
             fmt("%.6g", r.radiance.median) + "," + std::to_string(r.radiance.points) + "," +
             fmt("%.4g", r.ns_per_lookup) + "," + (r.planned ? "1" : "0") + "\n";
    return s;
}

std::string methods_csv(const std::vector<MethodRow> &rows) {
    std::string s = "method,ns_per_call,median_rel,p90_rel,p99_rel,max_rel,queries\n";
    for (const auto &r : rows) {
        auto e = [&](double v) { return r.reference ? std::string("reference") : fmt("%.6g", v); };
        s += r.name + "," + fmt("%.5g", r.ns_per_call) + "," + e(r.error.median) + "," + e(r.error.p90) + "," +
             e(r.error.p99) + "," + e(r.error.max) + "," + std::to_string(r.error.points) + "\n";
    }
    return s;
}

namespace {

// A plot with both axes logarithmic.
Plot log_log_plot(std::string title, std::string x_label, std::string y_label) {
    Plot p;
    p.title = std::move(title);
    p.x_label = std::move(x_label);
    p.y_label = std::move(y_label);
    p.log_x = p.log_y = true;
    return p;
}

} // namespace

Plot tolerance_plot(const std::string &kind, const std::vector<ToleranceRung> &rungs) {
    Plot p = log_log_plot(kind + ": integration tolerance ladder",
                          "generation time, in-process, median of interleaved rounds (ms)",
                          "max relative error at sampled nodes");
    PlotSeries s;
    s.label = "tolerance rungs";
    for (const auto &r : rungs) {
        s.points.push_back({r.median_ms, r.max_node_rel});
        s.point_labels.push_back("tol " + fmt("%.0e", r.tolerance));
        if (r.planned) p.markers.push_back({{r.median_ms, r.max_node_rel}, "planned"});
    }
    p.series.push_back(s);
    return p;
}

Plot resolution_plot(const std::string &kind, const std::vector<ResolutionRung> &rungs, double accepted) {
    Plot p = log_log_plot(kind + ": resolution ladder (radiance over the scene's domain)", "table size (bytes)",
                          "relative error of the sampled radiance");
    std::vector<PlotPoint> all;
    for (Storage st : {Storage::F32, Storage::F16}) {
        PlotSeries mx, p99;
        mx.label = std::string(to_string(st)) + " max";
        p99.label = std::string(to_string(st)) + " p99";
        p99.dashed = true;
        for (const auto &r : rungs) {
            if (r.storage != st) continue;
            mx.points.push_back({static_cast<double>(r.bytes), r.radiance.max});
            mx.point_labels.push_back(counts_text(r.counts));
            p99.points.push_back({static_cast<double>(r.bytes), r.radiance.p99});
            all.push_back({static_cast<double>(r.bytes), r.radiance.max});
            if (r.planned) p.markers.push_back({{static_cast<double>(r.bytes), r.radiance.max}, "planned"});
        }
        p.series.push_back(mx);
        p.series.push_back(p99);
    }
    PlotSeries front;
    front.label = "Pareto front (max)";
    front.points = pareto_front(all);
    front.dashed = true;
    p.series.push_back(front);
    p.hlines.push_back({accepted, "accepted error " + fmt("%.3g", accepted)});
    return p;
}

Plot methods_plot(const std::string &kind, const std::vector<MethodRow> &rows, double accepted) {
    Plot p = log_log_plot(kind + ": runtime methods for the same radiance", "time per radiance call (ns)",
                          "relative error vs exact (median, p99, max)");
    for (const auto &r : rows) {
        if (r.reference) {
            p.vlines.push_back({r.ns_per_call, "exact (the reference) " + fmt("%.3g", r.ns_per_call) + " ns"});
            continue;
        }
        PlotSeries s;
        s.label = r.name;
        s.points = {{r.ns_per_call, r.error.median}, {r.ns_per_call, r.error.p99}, {r.ns_per_call, r.error.max}};
        s.point_labels = {"median", "p99", "max"};
        if (r.name == "table") p.markers.push_back({{r.ns_per_call, r.error.max}, "planned table"});
        p.series.push_back(s);
    }
    p.hlines.push_back({accepted, "accepted error " + fmt("%.3g", accepted)});
    return p;
}

std::string markdown_section(const PlannedTable &t, Storage storage, const RadianceQueries &qs,
                             const std::vector<ToleranceRung> &tol, const std::vector<ResolutionRung> &res,
                             const std::vector<MethodRow> &methods) {
    const std::string kind = t.name();
    std::string md;
    const PlanTrial &chosen = *t.chosen_trial();
    md += "\n## " + kind + "\n\n";
    for (const auto &r : t.requested_by) md += "- asked for by medium '" + r.medium + "' with light '" + r.light + "': " + r.need + "\n";
    md += "- planned: " + counts_text(chosen.counts) + ", " + to_string(storage) + ", " +
          fmt("%.1f", static_cast<double>(chosen.bytes) / 1024.0) + " KiB, integration tolerance " +
          fmt("%.0e", planned_tolerance(t)) + "; " + t.verdict + "\n";
    md += "- radiance queries: " + std::to_string(qs.size()) + " (" + qs.description + ")\n";

    md += "\n### Integration tolerance\n\n![tolerance ladder](" + kind + "_tolerance.svg)\n\n";
    md += "At the planned resolution. Error: maximum over " + std::to_string(kToleranceNodes) +
          " random nodes against the finer independent panel rule the generator measures with.\n\n";
    md += "| tolerance | generation (ms) | max node error | |\n|---:|---:|---:|---|\n";
    for (const auto &r : tol)
        md += "| " + fmt("%.0e", r.tolerance) + " | " + fmt("%.3g", r.median_ms) + " | " + fmt("%.2e", r.max_node_rel) +
              " | " + (r.planned ? "planned" : "") + " |\n";

    md += "\n### Resolution and storage\n\n![resolution ladder](" + kind + "_resolution.svg)\n\n";
    md += "Radiance through the runtime (`" + std::string(t.kind->runtime_class()) +
          "::radiance`) against exact quadrature on the queries above; 'table max' is the generator's own "
          "measurement on the tabulated quantity over the whole table.\n\n";
    md += "| nodes | storage | KiB | table max | radiance max | radiance p99 | ns/lookup | |\n"
          "|---|---|---:|---:|---:|---:|---:|---|\n";
    for (const auto &r : res)
        md += "| " + counts_text(r.counts) + " | " + to_string(r.storage) + " | " +
              fmt("%.1f", static_cast<double>(r.bytes) / 1024.0) + " | " + fmt("%.2e", r.table_max_rel) + " | " +
              fmt("%.2e", r.radiance.max) + " | " + fmt("%.2e", r.radiance.p99) + " | " + fmt("%.3g", r.ns_per_lookup) +
              " | " + (r.planned ? "planned" : "") + " |\n";

    md += "\n### Runtime methods\n\n![runtime methods](" + kind + "_methods.svg)\n\n";
    md += "Error: relative to exact quadrature, over the radiance queries above.";
    md += t.kind->methods_note();
    md += "\n\n| method | what | ns/call | median | p90 | p99 | max |\n|---|---|---:|---:|---:|---:|---:|\n";
    for (const auto &r : methods) {
        auto e = [&](double v) { return r.reference ? std::string("reference") : fmt("%.2e", v); };
        md += "| " + r.name + " | " + r.what + " | " + fmt("%.4g", r.ns_per_call) + " | " + e(r.error.median) + " | " +
              e(r.error.p90) + " | " + e(r.error.p99) + " | " + e(r.error.max) + " |\n";
    }
    return md;
}

} // namespace scatterlut
