// scatterlut generator — `report`'s measurements: the integration-tolerance ladder, the
// resolution ladder and the runtime methods of one planned table (each kind supplies its
// adapters: kinds/table_kind.hpp). Their writers: report_writers.hpp; the command: report.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "kinds/table_kind.hpp"
#include "opencl_device.hpp"
#include "plan.hpp"

namespace scatterlut {

constexpr int kToleranceNodes = 400;    // nodes compared with the finer reference per rung
constexpr uint64_t kQuerySeed = 12;     // the scene's radiance queries

struct ErrorStats {
    double median = 0, p90 = 0, p99 = 0, max = 0;
    size_t points = 0;
};

// Median, p90, p99 and max of relative errors (+inf counts as the largest).
ErrorStats error_stats(const std::vector<double> &err);

// Runs every job `rounds` times, interleaved (job 0, 1, …, 0, 1, …), so that the machine's
// drift over minutes affects all of them alike; returns each job's median seconds.
std::vector<double> interleaved_median_seconds(int rounds, const std::vector<std::function<void()>> &jobs);

struct ToleranceRung {
    double tolerance = 0;
    double median_ms = 0;
    double max_node_rel = 0;
    bool planned = false;
};

struct ResolutionRung {
    std::vector<int> counts;
    Storage storage = Storage::F32;
    size_t bytes = 0;
    double table_max_rel = 0; // the generator's own measurement, on G̃ or E
    ErrorStats radiance;      // over the scene's queries
    double ns_per_lookup = 0;
    bool planned = false;
};

struct MethodRow {
    std::string name;
    std::string what;
    double ns_per_call = 0;
    ErrorStats error;
    bool reference = false; // the exact quadrature: the errors are measured against it
};

double planned_tolerance(const PlannedTable &t);

// Every tolerance of the ladder (and the planned one) at the planned resolution: generation
// time (median of `rounds` interleaved rounds) and the integration error (the generator's
// finer panel rule).
std::vector<ToleranceRung> tolerance_ladder(Device &device, const PlannedTable &t, int rounds);

// Node counts around the planned ones, in f16 and f32 (up to `max_bytes`, the planned one
// always): the table's own error, the radiance error over `qs`, ns per lookup.
std::vector<ResolutionRung> resolution_ladder(Device &device, const PlannedTable &t, const RadianceQueries &qs,
                                              const Provenance &provenance, Storage planned_storage, size_t max_bytes,
                                              int rounds, const std::function<void(double)> &progress);

// The kind's runtime methods over `qs`: time per call and error against exact quadrature.
std::vector<MethodRow> runtime_methods(const TableKind &kind, const Table &table, const RadianceQueries &qs,
                                       int rounds);

} // namespace scatterlut
