#include "report_spot.hpp"

#include <functional>
#include <vector>

#include "report_ladders.hpp"
#include "report_writers.hpp"
#include "spot_measure.hpp"
#include "text_format.hpp"
#include "scatterlut/airlight.hpp"

namespace scatterlut {
namespace {

constexpr uint64_t kReportSpotSeed = 14;
volatile double g_spot_sink = 0; // keeps the timed loops' results alive

struct Column {
    const char *name, *what;
    std::vector<double> SpotViewErrors::*errors;
};
const Column kColumns[] = {
    {"table", "the planned table: the ray cut at the cone, the band by parts (spot_airlight_radiance)",
     &SpotViewErrors::table},
    {"band_rule", "the same cuts and band rule with the exact point-light radiance: the rule's own error",
     &SpotViewErrors::band_rule},
    {"unclipped", "the whole ray as a point light (exact), no cone: NVIDIA's Rain sample",
     &SpotViewErrors::unclipped},
    {"closest_falloff", "that times the falloff at the ray's closest approach to the light",
     &SpotViewErrors::closest_falloff},
};

} // namespace

std::string spot_report_section(const PlannedTable &t, const Scene &scene, size_t rays_per_view, int rounds,
                                 const std::string &out_dir) {
    const std::optional<SpotServing> serving = t.kind->spot_serving(scene, t.plan, t.table);
    if (!serving) return "";
    const SpotMeasurement m = measure_spot_lights(*serving, rays_per_view, kReportSpotSeed);
    if (m.rays.empty()) return "";

    // Cost per call on every drawn ray: exact, the table path, and the table for the same ray
    // as a point light (what a spot costs over a point light of the same table).
    const double g = serving->phase_g;
    std::vector<AirlightQuery> as_point;
    for (const SpotQuery &q : m.rays)
        as_point.push_back(airlight_query_from_points(q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(),
                                                      q.length_m, q.sigma_s_per_m, q.sigma_a_per_m,
                                                      q.light.intensity_W_per_sr));
    const RadianceQueries point_queries{as_point, std::vector<double>(as_point.size(), 0.0), ""};
    const std::function<double(size_t)> point_table = t.kind->table_radiance(t.table, point_queries); // keeps a pointer
    const std::vector<std::function<void()>> jobs = {
        [&] {
            double s = 0;
            for (const SpotQuery &q : m.rays) s += spot_airlight_radiance_exact(q, g);
            g_spot_sink = s;
        },
        [&] {
            double s = 0;
            for (const SpotQuery &q : m.rays) s += serving->table_radiance(q);
            g_spot_sink = s;
        },
        [&] {
            double s = 0;
            for (size_t k = 0; k < point_queries.size(); ++k) s += point_table(k);
            g_spot_sink = s;
        }};
    for (const auto &j : jobs) j(); // warm-up
    std::vector<double> ns = interleaved_median_seconds(rounds, jobs);
    for (double &v : ns) v *= 1e9 / static_cast<double>(m.rays.size());

    const std::string kind = t.name();
    const double accepted = scene.relative_error;
    std::string md = "\n### Spot lights\n\n";
    md += "The scene's spot lights (docs/SPOT.md) through this table: each view ray cut at the cone, the inner "
          "cone's pieces from the table's radiance of each sub-segment, the falloff band by parts with an 8-point "
          "Gauss-Legendre rule. Rays: " + std::to_string(rays_per_view) + " per view (" + describe_spot_queries() +
          "); errors relative to the exact spot airlight (`spot_airlight_radiance_exact`), over the rays it lights "
          "(finite, positive radiance); the planner's check: " +
          (t.spot_max_rel >= 0 ? fmt("%.3g", t.spot_max_rel) : std::string("not run")) +
          " on its own rays against the scene's error " + fmt("%.3g", accepted) + ".\n\n";
    md += "| view | rays | lit | misses answered non-zero | method | median | p99 | max |\n"
          "|---|---:|---:|---:|---|---:|---:|---:|\n";
    std::string csv = "view,rays,lit,misses_answered_nonzero,method,median,p90,p99,max\n";
    for (const SpotViewErrors &v : m.views)
        for (const Column &c : kColumns) {
            const ErrorStats e = error_stats(v.*c.errors);
            md += std::string("| ") + spot_view_name(v.view) + " | " + std::to_string(v.rays) + " | " +
                  std::to_string(v.lit) + " | " + std::to_string(v.dark_answered) + " | " + c.name + " | " +
                  fmt("%.2e", e.median) + " | " + fmt("%.2e", e.p99) + " | " + fmt("%.2e", e.max) + " |\n";
            csv += std::string(spot_view_name(v.view)) + "," + std::to_string(v.rays) + "," + std::to_string(v.lit) +
                   "," + std::to_string(v.dark_answered) + "," + c.name + "," + fmt("%.6e", e.median) + "," +
                   fmt("%.6e", e.p90) + "," + fmt("%.6e", e.p99) + "," + fmt("%.6e", e.max) + "\n";
        }
    md += "\nMethods: ";
    for (const Column &c : kColumns) md += std::string("`") + c.name + "` " + c.what + "; ";
    md += "a miss answered non-zero is a ray that never meets the beam (exact 0) given light.\n\n";
    md += "Cost per call over all " + std::to_string(m.rays.size()) + " rays (median of " + std::to_string(rounds) +
          " interleaved rounds): exact " + fmt("%.4g", ns[0]) + " ns, the table path " + fmt("%.4g", ns[1]) +
          " ns, the same rays as point lights through the table " + fmt("%.4g", ns[2]) + " ns: a spot costs " +
          fmt("%.2f", ns[1] / ns[2]) + "x a point light here.\n";
    write_text(out_dir + "/" + kind + "_spot.csv", csv);
    return md;
}

} // namespace scatterlut
