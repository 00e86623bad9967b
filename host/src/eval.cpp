#include "eval.hpp"

#include "json_guard.hpp"

#include <cmath>
#include <istream>
#include <limits>
#include <ostream>
#include <stdexcept>

extern "C" {
#include "slut_airlight.h"
#include "slut_nearlight.h"
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

// The fields put() answered null for a non-finite value, collected under this key and
// turned into a "note" by eval_query (never a silent null).
constexpr const char *kNonFiniteKey = "\x01nonfinite";

// JSON has no infinity: a non-finite answer is null, and eval_query's note says why.
void put(nlohmann::json &out, const char *name, double value) {
    if (std::isfinite(value)) {
        out[name] = value;
        return;
    }
    out[name] = nullptr;
    out[kNonFiniteKey].push_back({name, std::isnan(value) ? "nan" : value > 0 ? "+inf" : "-inf"});
}

// One note for the fields answered null: +inf is an overflow of the double range (the
// airlight's ray through the light has its own note), NaN a value these extreme inputs do
// not allow in double precision.
void note_non_finite(nlohmann::json &out) {
    if (!out.contains(kNonFiniteKey)) return;
    std::string overflow, nan;
    for (const auto &f : out[kNonFiniteKey]) {
        std::string &list = f[1] == "nan" ? nan : overflow;
        list += (list.empty() ? "" : ", ") + f[0].get<std::string>();
    }
    out.erase(kNonFiniteKey);
    if (out.contains("note")) return;
    std::string note;
    if (!overflow.empty())
        note = "null for " + overflow + ": beyond the largest double (1.8e308), infinite";
    if (!nan.empty())
        note += (note.empty() ? "" : "; ") + std::string("null for ") + nan +
                ": not computable in double precision at these extreme inputs (an intermediate overflows)";
    out["note"] = note;
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
    const bool through_light = a.gamma_rad == 0.0 && a.length_m >= a.distance_m;
    if (through_light) out["note"] = "diverges: the view ray passes through the light";
    if (tables.airlight.empty()) out["table"] = nullptr;
    else put(out, "table", tables.airlight.front().radiance(a));
}

// The first near-light table covering (T, g, r, S), or null.
const NearLightTable *covering(const EvalTables &tables, double T, double g, double r, double S) {
    for (const auto &t : tables.near_light)
        if (t.covers(T, g, r, S)) return &t;
    return nullptr;
}

void vector_field(const nlohmann::json &q, const char *name, double *out) {
    if (!q.contains(name) || !q.at(name).is_array() || q.at(name).size() != 3)
        throw std::invalid_argument(std::string("field \"") + name + "\" must be an array of 3 numbers");
    for (size_t k = 0; k < 3; ++k) {
        if (!q.at(name).at(k).is_number()) throw std::invalid_argument(std::string("field \"") + name + "\" must hold numbers");
        out[k] = q.at(name).at(k).get<double>();
    }
}

void answer_N(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    const double T = number_field(q, "T"), g = number_field(q, "g"), r = number_field(q, "r"), S = number_field(q, "S");
    if (!(T > 0.0) || !std::isfinite(T)) throw std::invalid_argument("T must be finite and > 0");
    if (!(g >= -1.0 && g <= 1.0)) throw std::invalid_argument("g must lie in [-1, 1]");
    if (!(r >= 0.0)) throw std::invalid_argument("r must be >= 0");
    if (!(S >= 0.0)) throw std::invalid_argument("S must be >= 0 (or \"inf\")");
    const double H = slut_nl_H(T, g, S), E = slut_nl_E(T, g, r, S);
    put(out, "exact", (H > 0.0 && std::isfinite(H)) ? E * H : H);
    put(out, "E", E);
    put(out, "H", H);
    const NearLightTable *t = covering(tables, T, g, r, S);
    if (t) put(out, "table", t->E(T, g, r, S) * H);
    else out["table"] = nullptr;
    put(out, "approx", slut_nl_N_thin(T, g, r, S));
}

void answer_near_light(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    NearLightQuery n;
    n.sigma_s_per_m = number_field(q, "sigma_s");
    n.sigma_a_per_m = number_field(q, "sigma_a");
    n.intensity_W_per_sr = number_field(q, "intensity");
    vector_field(q, "normal", n.normal);
    vector_field(q, "eye_dir", n.eye_dir);
    vector_field(q, "light_pos", n.light_rel_m);
    n.length_m = number_field(q, "length");
    if (q.contains("eta")) n.eta = number_field(q, "eta");
    if (q.contains("fresnel")) {
        if (!q.at("fresnel").is_boolean()) throw std::invalid_argument("field \"fresnel\" must be true or false");
        n.fresnel = q.at("fresnel").get<bool>();
    }
    put(out, "exact", near_light_radiance_exact(n)); // validates the query
    const NearLightParams p = near_light_params(n);
    const NearLightTable *t = p.light_below ? nullptr : covering(tables, p.T, p.g, p.r, p.S);
    if (t) put(out, "table", t->radiance(n));
    else if (p.light_below && !tables.near_light.empty()) out["table"] = 0.0;
    else out["table"] = nullptr;
    put(out, "approx", near_light_radiance_thin(n));
    put(out, "distant", near_light_radiance_distant(n));
}

} // namespace

nlohmann::json eval_query(const nlohmann::json &query, const EvalTables &tables) {
    if (!query.is_object()) throw std::invalid_argument("a query must be a JSON object");
    if (!query.contains("quantity") || !query.at("quantity").is_string())
        throw std::invalid_argument("missing string field \"quantity\" (F, airlight, N or near_light)");
    const std::string quantity = query.at("quantity").get<std::string>();
    nlohmann::json out = query;
    out.erase(kNonFiniteKey); // put()'s bookkeeping key, never a query's
    if (quantity == "F") answer_F(query, out, tables);
    else if (quantity == "airlight") answer_airlight(query, out, tables);
    else if (quantity == "N") answer_N(query, out, tables);
    else if (quantity == "near_light") answer_near_light(query, out, tables);
    else throw std::invalid_argument("unknown quantity \"" + quantity + "\" (expected F, airlight, N or near_light)");
    note_non_finite(out);
    return out;
}

namespace {

// Reads one line (without its '\n') into `line`, keeping at most kMaxEvalLineBytes: the
// rest of a longer line is read and dropped, `too_long` set. False at end of input.
bool read_bounded_line(std::istream &in, std::string &line, bool &too_long) {
    line.clear();
    too_long = false;
    std::streambuf *buf = in.rdbuf();
    bool any = false;
    for (;;) {
        const int c = buf->sbumpc();
        if (c == std::char_traits<char>::eof()) {
            in.setstate(std::ios::eofbit);
            return any;
        }
        any = true;
        if (c == '\n') return true;
        if (line.size() < kMaxEvalLineBytes) line.push_back(static_cast<char>(c));
        else too_long = true;
    }
}

} // namespace

int eval_stream(std::istream &in, std::ostream &out, const EvalTables &tables) {
    std::string line;
    int line_number = 0, errors = 0;
    bool too_long = false;
    while (read_bounded_line(in, line, too_long)) {
        ++line_number;
        const std::string at = "line " + std::to_string(line_number) + ": ";
        nlohmann::json answer;
        std::string problem;
        if (too_long) problem = "longer than " + std::to_string(kMaxEvalLineBytes) + " bytes (not read)";
        else if (line.find_first_not_of(" \t\r") == std::string::npos) problem = "blank line, expected a JSON object";
        else problem = json_text_problem(line, kMaxEvalNesting);
        if (!problem.empty()) {
            answer = {{"error", at + problem}};
            ++errors;
        } else {
            try {
                answer = eval_query(nlohmann::json::parse(line), tables);
            } catch (const nlohmann::json::exception &e) {
                answer = {{"error", at + "invalid JSON: " + e.what()}};
                ++errors;
            } catch (const std::exception &e) {
                answer = {{"error", at + e.what()}};
                ++errors;
            }
        }
        // The query is echoed: its strings are valid UTF-8 (checked above); replace keeps a
        // message quoting the line valid whatever it holds.
        out << answer.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
        out.flush();
    }
    return errors;
}

} // namespace scatterlut
