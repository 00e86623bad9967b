#include "eval.hpp"

#include "json_guard.hpp"

#include <algorithm>
#include <cmath>
#include <istream>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "scatterlut/io.hpp"

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
