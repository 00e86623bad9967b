#include "eval.hpp"

#include <cmath>
#include <istream>
#include <limits>
#include <ostream>
#include <stdexcept>

extern "C" {
#include "slut_airlight.h"
}

namespace scatterlut {
namespace {

double number_field(const nlohmann::json &q, const char *name) {
    if (!q.contains(name)) throw std::invalid_argument(std::string("missing field \"") + name + "\"");
    const auto &v = q.at(name);
    if (v.is_number()) return v.get<double>();
    if (v.is_string() && (v.get<std::string>() == "inf" || v.get<std::string>() == "infinity"))
        return std::numeric_limits<double>::infinity();
    throw std::invalid_argument(std::string("field \"") + name + "\" must be a number");
}

// JSON has no infinity: a non-finite answer is null, with a note saying why.
void put(nlohmann::json &out, const char *name, double value) {
    if (std::isfinite(value)) out[name] = value;
    else out[name] = nullptr;
}

void answer_F(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    const double u = number_field(q, "u"), v = number_field(q, "v");
    if (!(u >= 0.0) || !std::isfinite(u)) throw std::invalid_argument("u must be finite and >= 0");
    if (!(v >= 0.0) || !(v <= 1.5707963267948968)) throw std::invalid_argument("v must lie in [0, pi/2]");
    put(out, "exact", slut_F_quadrature(u, v));
    put(out, "tail", slut_tail_quadrature(u, v));
    if (tables.airlight.empty()) {
        out["table"] = nullptr;
        out["table_tail"] = nullptr;
    } else {
        put(out, "table", tables.airlight.front().F(u, v));
        put(out, "table_tail", tables.airlight.front().tail(u, v));
    }
}

void answer_airlight(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    AirlightQuery a;
    a.sigma_s_per_m = number_field(q, "sigma_s");
    a.sigma_a_per_m = number_field(q, "sigma_a");
    a.intensity_W_per_sr = number_field(q, "intensity");
    a.distance_m = number_field(q, "distance");
    a.gamma_rad = number_field(q, "gamma");
    a.length_m = number_field(q, "length");
    const double exact = airlight_radiance_exact(a); // validates the query
    put(out, "exact", exact);
    if (std::isinf(exact)) out["note"] = "diverges: the view ray passes through the light";
    if (tables.airlight.empty()) out["table"] = nullptr;
    else put(out, "table", tables.airlight.front().radiance(a));
}

} // namespace

nlohmann::json eval_query(const nlohmann::json &query, const EvalTables &tables) {
    if (!query.is_object()) throw std::invalid_argument("a query must be a JSON object");
    if (!query.contains("quantity") || !query.at("quantity").is_string())
        throw std::invalid_argument("missing string field \"quantity\" (\"F\" or \"airlight\")");
    const std::string quantity = query.at("quantity").get<std::string>();
    nlohmann::json out = query;
    if (quantity == "F") answer_F(query, out, tables);
    else if (quantity == "airlight") answer_airlight(query, out, tables);
    else throw std::invalid_argument("unknown quantity \"" + quantity + "\" (expected \"F\" or \"airlight\")");
    return out;
}

int eval_stream(std::istream &in, std::ostream &out, const EvalTables &tables) {
    std::string line;
    int line_number = 0, errors = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        nlohmann::json answer;
        try {
            answer = eval_query(nlohmann::json::parse(line), tables);
        } catch (const nlohmann::json::exception &e) {
            answer = {{"error", "line " + std::to_string(line_number) + ": invalid JSON: " + e.what()}};
            ++errors;
        } catch (const std::exception &e) {
            answer = {{"error", "line " + std::to_string(line_number) + ": " + e.what()}};
            ++errors;
        }
        out << answer.dump() << '\n';
        out.flush();
    }
    return errors;
}

} // namespace scatterlut
