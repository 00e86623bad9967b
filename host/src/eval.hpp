// scatterlut generator — `eval`: JSON lines in, JSON lines out. Per query the exact
// integral (double-precision quadrature), the table sample and, where they exist, the
// closed forms side by side. How tests and users probe a table.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scatterlut/airlight.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// The tables eval samples, by kind; each query uses the first table that covers it.
struct EvalTables {
    std::vector<AirlightTable> airlight;
    std::vector<NearLightTable> near_light; // E3 and E4 tables
};

// Answers one parsed query: the query's fields plus the answer fields. Throws
// std::invalid_argument with a message for a malformed query.
nlohmann::json eval_query(const nlohmann::json &query, const EvalTables &tables);

// Reads JSON lines from `in` until EOF and writes one JSON line per input line to `out`,
// in order; a bad line yields {"error": "line N: …"} and processing continues. Blank
// lines are skipped. Returns the number of error lines.
int eval_stream(std::istream &in, std::ostream &out, const EvalTables &tables);

} // namespace scatterlut
