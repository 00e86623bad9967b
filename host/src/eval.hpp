// scatterlut generator — `eval`: JSON lines in, JSON lines out. Per query the exact
// integral (double-precision quadrature), the table sample and, where they exist, the
// closed forms side by side. How tests and users probe a table.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "kinds/runtime_kind.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// The tables eval samples, in the order given; each query uses the first table of a kind
// that answers it and covers it.
struct EvalTables {
    std::vector<std::shared_ptr<const RuntimeSampler>> samplers;

    // Loads `table` through its kind's runtime sampler; throws LoadError naming `path` for a
    // kind eval does not know.
    void add(const std::string &path, Table table);
};

// The fields of a query, for the kinds' answers (answer_eval): a number (or "inf"), an
// array of 3 numbers; std::invalid_argument naming the field when missing or malformed.
double eval_number_field(const nlohmann::json &q, const char *name);
void eval_vector_field(const nlohmann::json &q, const char *name, double *out);
// Puts a number into an answer; a non-finite one is null, with a note eval_query adds.
void eval_put(nlohmann::json &out, const char *name, double value);
// The physical query of an "airlight" / "near_light" line (fields as docs say; eta and fresnel
// optional). Throws std::invalid_argument naming the field that is missing or not a number.
AirlightQuery eval_airlight_query(const nlohmann::json &q);
NearLightQuery eval_near_light_query(const nlohmann::json &q);
// A "spot_airlight" line of one channel (σ as numbers; phase_g given apart): "exact"
// (scatterlut/spot.hpp) and "table" from a loaded airlight table of that g, else null; a ray
// through the lit apex answers null with a note (kinds/airlight_runtime.cpp).
void answer_spot_airlight(const nlohmann::json &q, double phase_g, nlohmann::json &out, const EvalTables &tables);

// Answers one parsed query: the query's fields plus the answer fields. Throws
// std::invalid_argument with a message for a malformed query.
nlohmann::json eval_query(const nlohmann::json &query, const EvalTables &tables);

// Bounds on one eval input line, checked before it is parsed: a line is read up to
// kMaxEvalLineBytes (the rest of a longer line is skipped unread into memory), and its
// arrays/objects may nest kMaxEvalNesting deep (a query needs 2).
inline constexpr size_t kMaxEvalLineBytes = 1 << 20;
inline constexpr int kMaxEvalNesting = 64;

// Reads JSON lines from `in` until EOF and writes exactly one JSON line per input line to
// `out`, in order; a bad line (invalid JSON or UTF-8, too long, too deep, a bad query)
// yields {"error": "line N: …"} and processing continues. A blank line (only spaces, tabs,
// CR) is answered {"error": "line N: blank line, expected a JSON object"}. Returns the
// number of error lines.
int eval_stream(std::istream &in, std::ostream &out, const EvalTables &tables);

} // namespace scatterlut
