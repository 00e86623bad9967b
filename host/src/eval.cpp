#include "eval.hpp"

#include "json_guard.hpp"

#include <algorithm>
#include <cmath>
#include <istream>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/anisotropic.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/nearlight_hg.hpp"

namespace scatterlut {
namespace {

// The fields put() answered null for a non-finite value, collected under this key and
// turned into a "note" by eval_query (never a silent null).
constexpr const char *kNonFiniteKey = "\x01nonfinite";

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


// ------------------------------------------------ phase_g and per-channel coefficients
// "airlight" and "near_light" queries may carry "phase_g" (Henyey–Greenstein asymmetry,
// default 0) and sigma_s / sigma_a as arrays of 3 (r, g, b). Each channel is one scalar
// query (the integrals are dimensionless in σ_t times a length, so one table serves every
// channel); with arrays, every answer field is an array of 3. phase_g = 0 with numbers is
// exactly the isotropic answer of the kind (the same code).

bool is_medium_quantity(const std::string &quantity) {
    return quantity == "airlight" || quantity == "near_light" || quantity == "spot_airlight";
}

// The query's phase_g (0 when absent); std::invalid_argument when not a number or out of range.
double eval_phase_g(const nlohmann::json &q) {
    if (!q.contains("phase_g")) return 0.0;
    if (!q.at("phase_g").is_number()) throw std::invalid_argument("field \"phase_g\" must be a number");
    const double g = q.at("phase_g").get<double>();
    if (!(std::isfinite(g) && std::fabs(g) <= 0.999999))
        throw std::invalid_argument("field \"phase_g\" (Henyey-Greenstein asymmetry) must lie in [-0.999999, 0.999999]");
    return g;
}

// A coefficient field: a number (every channel) or an array of exactly 3 numbers.
Rgb eval_channels(const nlohmann::json &q, const char *name) {
    if (q.contains(name) && q.at(name).is_array()) {
        Rgb c{};
        eval_vector_field(q, name, c.data());
        return c;
    }
    const double x = eval_number_field(q, name);
    return {x, x, x};
}

// The anisotropic airlight (phase_g ≠ 0) of one channel: exact by quadrature (anisotropic.hpp),
// the table from a loaded anisotropic airlight table of the same g.
void answer_airlight_phase(const nlohmann::json &q, double phase_g, nlohmann::json &out, const EvalTables &tables) {
    const AirlightQuery a = eval_airlight_query(q);
    eval_put(out, "exact", airlight_radiance_exact(a, phase_g)); // validates the query
    if (a.gamma_rad == 0.0 && a.length_m >= a.distance_m) out["note"] = "diverges: the view ray passes through the light";
    // A table answers only a query of its own g (it covers every u and w: asymptotic forms beyond its axes).
    const AirlightHgTable *table =
        first_runtime<AirlightHgTable>(tables.samplers, [&](const AirlightHgTable &t) { return t.serves(phase_g); });
    if (table) eval_put(out, "table", table->radiance(a));
    else out["table"] = nullptr;
}

// The anisotropic near light (phase_g ≠ 0) of one channel: exact by quadrature; the table from
// a loaded anisotropic near-light table (E3_hg or E4_hg) of the same g that covers the query
// (the light below the plane: 0 when one of that g is loaded); "approx" and "distant", the
// thin-medium and distant-light closed forms with the phase (nearlight_hg.hpp), as the isotropic
// query gives its own.
void answer_near_light_phase(const nlohmann::json &q, double phase_g, nlohmann::json &out, const EvalTables &tables) {
    const NearLightQuery n = eval_near_light_query(q);
    eval_put(out, "exact", near_light_radiance_exact(n, phase_g)); // validates the query
    const NearLightParams p = near_light_params(n);
    const NearLightHgTable *table = first_runtime<NearLightHgTable>(tables.samplers, [&](const NearLightHgTable &t) {
        return t.phase_g() == phase_g && (p.light_below || t.covers(p.T, p.g, p.r, p.S));
    });
    if (!table) out["table"] = nullptr;
    else if (p.light_below) out["table"] = 0.0;
    else eval_put(out, "table", table->radiance(n));
    eval_put(out, "approx", near_light_radiance_thin(n, phase_g));
    eval_put(out, "distant", near_light_radiance_distant(n, phase_g));
}

// One channel's answer fields (those not in the query), with its note for non-finite values.
nlohmann::json channel_answer(const RuntimeKind &kind, const std::string &quantity, const nlohmann::json &query,
                              double sigma_s, double sigma_a, double phase_g, const EvalTables &tables) {
    nlohmann::json q = query;
    q["sigma_s"] = sigma_s;
    q["sigma_a"] = sigma_a;
    q.erase("phase_g");
    nlohmann::json out = nlohmann::json::object();
    if (quantity == "spot_airlight") answer_spot_airlight(q, phase_g, out, tables);
    else if (phase_g == 0.0) kind.answer_eval(quantity, q, out, tables);
    else if (quantity == "airlight") answer_airlight_phase(q, phase_g, out, tables);
    else answer_near_light_phase(q, phase_g, out, tables);
    note_non_finite(out);
    return out;
}

// Answers a medium query with phase_g and/or per-channel coefficients into `out`.
void answer_medium_query(const RuntimeKind &kind, const std::string &quantity, const nlohmann::json &query,
                         nlohmann::json &out, const EvalTables &tables) {
    const double phase_g = eval_phase_g(query);
    const bool rgb = (query.contains("sigma_s") && query.at("sigma_s").is_array()) ||
                     (query.contains("sigma_a") && query.at("sigma_a").is_array());
    const Rgb sigma_s = eval_channels(query, "sigma_s"), sigma_a = eval_channels(query, "sigma_a");
    if (!rgb) {
        const nlohmann::json a = channel_answer(kind, quantity, query, sigma_s[0], sigma_a[0], phase_g, tables);
        for (auto it = a.begin(); it != a.end(); ++it) out[it.key()] = it.value();
        return;
    }
    nlohmann::json channels[3];
    for (int c = 0; c < 3; ++c)
        channels[c] = channel_answer(kind, quantity, query, sigma_s[c], sigma_a[c], phase_g, tables);
    // Every answer field as [r, g, b] (null where a channel has none); notes joined per channel.
    std::vector<std::string> fields;
    for (const auto &a : channels)
        for (auto it = a.begin(); it != a.end(); ++it)
            if (it.key() != "note" && std::find(fields.begin(), fields.end(), it.key()) == fields.end())
                fields.push_back(it.key());
    for (const std::string &f : fields) {
        nlohmann::json v = nlohmann::json::array();
        for (const auto &a : channels) v.push_back(a.contains(f) ? a[f] : nlohmann::json(nullptr));
        out[f] = v;
    }
    static const char *const kChannel[3] = {"r", "g", "b"};
    std::string note;
    const bool same = channels[0].value("note", "") == channels[1].value("note", "") &&
                      channels[1].value("note", "") == channels[2].value("note", "");
    for (int c = 0; c < 3; ++c) {
        if (!channels[c].contains("note")) continue;
        if (same) {
            note = channels[c]["note"].get<std::string>();
            break;
        }
        note += (note.empty() ? "" : "; ") + std::string(kChannel[c]) + ": " + channels[c]["note"].get<std::string>();
    }
    if (!note.empty()) out["note"] = note;
}

} // namespace

double eval_number_field(const nlohmann::json &q, const char *name) {
    if (!q.contains(name)) throw std::invalid_argument(std::string("missing field \"") + name + "\"");
    const auto &v = q.at(name);
    if (v.is_number()) return v.get<double>();
    if (v.is_string() && (v.get<std::string>() == "inf" || v.get<std::string>() == "infinity"))
        return std::numeric_limits<double>::infinity();
    throw std::invalid_argument(std::string("field \"") + name + "\" must be a number");
}


// JSON has no infinity: a non-finite answer is null, and eval_query's note says why.
void eval_put(nlohmann::json &out, const char *name, double value) {
    if (std::isfinite(value)) {
        out[name] = value;
        return;
    }
    out[name] = nullptr;
    out[kNonFiniteKey].push_back({name, std::isnan(value) ? "nan" : value > 0 ? "+inf" : "-inf"});
}

AirlightQuery eval_airlight_query(const nlohmann::json &q) {
    AirlightQuery a;
    a.sigma_s_per_m = eval_number_field(q, "sigma_s");
    a.sigma_a_per_m = eval_number_field(q, "sigma_a");
    a.intensity_W_per_sr = eval_number_field(q, "intensity");
    a.distance_m = eval_number_field(q, "distance");
    a.gamma_rad = eval_number_field(q, "gamma");
    a.length_m = eval_number_field(q, "length");
    return a;
}

NearLightQuery eval_near_light_query(const nlohmann::json &q) {
    NearLightQuery n;
    n.sigma_s_per_m = eval_number_field(q, "sigma_s");
    n.sigma_a_per_m = eval_number_field(q, "sigma_a");
    n.intensity_W_per_sr = eval_number_field(q, "intensity");
    eval_vector_field(q, "normal", n.normal);
    eval_vector_field(q, "eye_dir", n.eye_dir);
    eval_vector_field(q, "light_pos", n.light_rel_m);
    n.length_m = eval_number_field(q, "length");
    if (q.contains("eta")) n.eta = eval_number_field(q, "eta");
    if (q.contains("fresnel")) {
        if (!q.at("fresnel").is_boolean()) throw std::invalid_argument("field \"fresnel\" must be true or false");
        n.fresnel = q.at("fresnel").get<bool>();
    }
    return n;
}

void eval_vector_field(const nlohmann::json &q, const char *name, double *out) {
    if (!q.contains(name) || !q.at(name).is_array() || q.at(name).size() != 3)
        throw std::invalid_argument(std::string("field \"") + name + "\" must be an array of 3 numbers");
    for (size_t k = 0; k < 3; ++k) {
        if (!q.at(name).at(k).is_number()) throw std::invalid_argument(std::string("field \"") + name + "\" must hold numbers");
        out[k] = q.at(name).at(k).get<double>();
    }
}

void EvalTables::add(const std::string &path, Table table) {
    const RuntimeKind *kind = find_runtime_kind(table.kind);
    if (!kind) throw LoadError(path + ": table kind '" + table.kind + "' is not one eval knows");
    samplers.push_back(kind->make_sampler(std::move(table)));
}

nlohmann::json eval_query(const nlohmann::json &query, const EvalTables &tables) {
    if (!query.is_object()) throw std::invalid_argument("a query must be a JSON object");
    // The quantities the kinds answer, in registry order: "F, airlight, N or near_light".
    std::vector<std::string> known;
    for (const RuntimeKind *k : runtime_kinds())
        for (const std::string &q : k->eval_quantities())
            if (std::find(known.begin(), known.end(), q) == known.end()) known.push_back(q);
    std::string list;
    for (size_t i = 0; i < known.size(); ++i) list += (i == 0 ? "" : i + 1 == known.size() ? " or " : ", ") + known[i];
    if (!query.contains("quantity") || !query.at("quantity").is_string())
        throw std::invalid_argument("missing string field \"quantity\" (" + list + ")");
    const std::string quantity = query.at("quantity").get<std::string>();
    nlohmann::json out = query;
    out.erase(kNonFiniteKey); // eval_put()'s bookkeeping key, never a query's
    const RuntimeKind *answering = nullptr;
    for (const RuntimeKind *k : runtime_kinds()) {
        const std::vector<std::string> q = k->eval_quantities();
        if (std::find(q.begin(), q.end(), quantity) != q.end()) {
            answering = k;
            break;
        }
    }
    if (!answering) throw std::invalid_argument("unknown quantity \"" + quantity + "\" (expected " + list + ")");
    if (!is_medium_quantity(quantity)) {
        if (query.contains("phase_g"))
            throw std::invalid_argument("field \"phase_g\" applies to airlight, spot_airlight and near_light queries only");
        answering->answer_eval(quantity, query, out, tables);
        note_non_finite(out);
        return out;
    }
    const bool plain = !query.contains("phase_g") && !(query.contains("sigma_s") && query.at("sigma_s").is_array()) &&
                       !(query.contains("sigma_a") && query.at("sigma_a").is_array());
    if (!plain) {
        answer_medium_query(*answering, quantity, query, out, tables);
        return out;
    }
    answering->answer_eval(quantity, query, out, tables);
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
