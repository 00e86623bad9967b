#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <set>
#include <optional>
#include <sstream>

#include <toml++/toml.h>

#include "embedded_kernels.hpp"
#include "json_guard.hpp"
#include "scatterlut/io.hpp"

// The scenes embedded at build time (host/scenes/*.toml, cmake/embed_kernels.cmake).
namespace scatterlut::embedded {
extern const EmbeddedFile kSceneFiles[];
extern const std::size_t kSceneFileCount;
} // namespace scatterlut::embedded

namespace scatterlut {
namespace {

const char *const kLengthExpected = "a length in [1e-6, 1e6] m";
const char *const kSigmaExpected = "a coefficient in [0, 1e6] (1/m)";
const char *const kSigmaOrRgbExpected = "a coefficient in [0, 1e6] (1/m) or an [r, g, b] triple of them";
const char *const kPhaseGExpected =
    "a Henyey-Greenstein asymmetry g in [-0.99, 0.99] (0 isotropic, > 0 forward; beyond 0.99 the forward peak "
    "is too narrow to tabulate)";
const char *const kRelativeErrorExpected =
    "a relative error on radiance in [1e-9, 0.5] (double-precision quadrature and storage reach ~1e-10)";

// Messages: "FILE:LINE:COL: key 'path': expected …". Every check below goes through one
// Reader so that each names the file, the place and the key's full dotted path.
class Reader {
public:
    explicit Reader(std::string source) : source_(std::move(source)) {}

    [[noreturn]] void fail(const toml::source_region &at, const std::string &key, const std::string &what) const {
        std::ostringstream msg;
        msg << source_ << ":" << at.begin.line << ":" << at.begin.column << ": key '" << key << "': " << what;
        throw SceneError(msg.str());
    }

    // Refuses keys of `table` not in `known`.
    void only_keys(const toml::table &table, const std::string &path, std::initializer_list<const char *> known) const {
        for (const auto &entry : table) {
            const auto &key = entry.first; // not a structured binding: lambdas capture it (clang, C++17)
            const bool ok = std::any_of(known.begin(), known.end(), [&](const char *k) { return key.str() == k; });
            if (ok) continue;
            std::string list;
            for (const char *k : known) list += (list.empty() ? "" : ", ") + std::string(k);
            fail(key.source(), join(path, std::string(key.str())), "expected one of " + list + " (unknown key)");
        }
    }

    const toml::table *table(const toml::table &parent, const char *key, const std::string &path) const {
        const toml::node *n = parent.get(key);
        if (!n) return nullptr;
        if (!n->is_table()) fail(n->source(), join(path, key), "expected a table ([" + join(path, key) + "])");
        return n->as_table();
    }

    // A finite number (integer or floating point) with lo ≤ x (or lo < x) and x ≤ hi.
    double number(const toml::table &t, const char *key, const std::string &path, bool required, double fallback,
                  double lo, bool lo_open, double hi, const std::string &expect) const {
        const toml::node *n = t.get(key);
        if (!n) {
            if (required) fail(t.source(), join(path, key), "expected " + expect + " (missing)");
            return fallback;
        }
        return number_value(*n, join(path, key), lo, lo_open, hi, expect);
    }

    double number_value(const toml::node &n, const std::string &key, double lo, bool lo_open, double hi,
                        const std::string &expect) const {
        if (!n.is_number()) fail(n.source(), key, "expected " + expect + ", got " + type_name(n));
        const double x = n.value<double>().value_or(std::nan(""));
        if (!std::isfinite(x)) fail(n.source(), key, "expected " + expect + ", got " + shown(x));
        if (x < lo || (lo_open && x == lo) || x > hi) fail(n.source(), key, "expected " + expect + ", got " + shown(x));
        return x;
    }

    std::string string(const toml::table &t, const char *key, const std::string &path, bool required,
                       const std::string &fallback, std::initializer_list<const char *> allowed = {}) const {
        const toml::node *n = t.get(key);
        if (!n) {
            if (required) fail(t.source(), join(path, key), "expected a string (missing)");
            return fallback;
        }
        if (!n->is_string()) fail(n->source(), join(path, key), "expected a string, got " + type_name(*n));
        const std::string s = n->value<std::string>().value_or("");
        if (allowed.size() == 0) {
            if (s.empty()) fail(n->source(), join(path, key), "expected a non-empty string");
            return s;
        }
        std::string list;
        for (const char *a : allowed) {
            if (s == a) return s;
            list += (list.empty() ? "" : ", ") + std::string("'") + a + "'";
        }
        fail(n->source(), join(path, key), "expected one of " + list + ", got '" + s + "'");
    }

    bool boolean(const toml::table &t, const char *key, const std::string &path, bool required, bool fallback) const {
        const toml::node *n = t.get(key);
        if (!n) {
            if (required) fail(t.source(), join(path, key), "expected true or false (missing)");
            return fallback;
        }
        if (!n->is_boolean()) fail(n->source(), join(path, key), "expected true or false, got " + type_name(*n));
        return n->value<bool>().value_or(false);
    }

    // A coefficient as a number (every channel) or an [r, g, b] triple, each in [0, hi].
    std::array<double, 3> number_or_rgb(const toml::table &t, const char *key, const std::string &path, double hi,
                                        const std::string &expect) const {
        const toml::node *n = t.get(key);
        if (!n) fail(t.source(), join(path, key), "expected " + expect + " (missing)");
        if (const toml::array *a = n->as_array()) {
            if (a->size() != 3)
                fail(n->source(), join(path, key),
                     "expected " + expect + ", got an array of " + std::to_string(a->size()) + " values");
            std::array<double, 3> rgb{};
            for (size_t c = 0; c < 3; ++c)
                rgb[c] = number_value(*a->get(c), join(path, key) + "[" + std::to_string(c) + "]", 0.0, false, hi,
                                      kSigmaExpected);
            return rgb;
        }
        // A single number keeps the grey medium's message (the triple is named when an array is wrong).
        const double x = number_value(*n, join(path, key), 0.0, false, hi,
                                      n->is_number() ? kSigmaExpected : expect);
        return {x, x, x};
    }

    // [min, max] with 0 < min ≤ max, both finite (lengths in m).
    Range range(const toml::node &n, const std::string &key) const {
        const char *expect = "[min, max] in m with 0 < min <= max";
        const toml::array *a = n.as_array();
        if (!a || a->size() != 2) fail(n.source(), key, std::string("expected ") + expect + ", got " + type_name(n));
        Range r;
        r.min = number_value(*a->get(0), key + "[0]", kSceneMinLength_m, false, kSceneMaxLength_m, kLengthExpected);
        r.max = number_value(*a->get(1), key + "[1]", kSceneMinLength_m, false, kSceneMaxLength_m, kLengthExpected);
        if (r.min > r.max)
            fail(n.source(), key, std::string("expected ") + expect + ", got an inverted range [" + shown(r.min) + ", " +
                                      shown(r.max) + "]");
        return r;
    }

    static std::string join(const std::string &path, const std::string &key) {
        return path.empty() ? key : path + "." + key;
    }

private:
    static std::string type_name(const toml::node &n) {
        switch (n.type()) {
        case toml::node_type::table: return "a table";
        case toml::node_type::array: return "an array";
        case toml::node_type::string: return "a string";
        case toml::node_type::integer: return "an integer";
        case toml::node_type::floating_point: return "a number";
        case toml::node_type::boolean: return "a boolean";
        default: return "a date or time";
        }
    }
    static std::string shown(double x) {
        std::ostringstream s;
        s.precision(6);
        s << x;
        return s.str();
    }
    std::string source_;
};

// surfaces = { diffuse = …, phong_exponents = […], light_distance_m = [min, max] } (or a
// [medium.surfaces] table): at least one of diffuse = true and a non-empty exponent list.
SceneSurfaces read_surfaces(const Reader &rd, const toml::node &n, const std::string &path) {
    if (!n.is_table()) rd.fail(n.source(), path, "expected a table { diffuse, phong_exponents, light_distance_m }");
    const toml::table &t = *n.as_table();
    rd.only_keys(t, path, {"diffuse", "phong_exponents", "light_distance_m"});
    SceneSurfaces s;
    s.line = static_cast<int>(t.source().begin.line);
    s.diffuse = rd.boolean(t, "diffuse", path, false, false);
    const std::string expect = "an integer Phong exponent in [1, " + std::to_string(kSceneMaxPhongExponent) + "]";
    if (const toml::node *e = t.get("phong_exponents")) {
        const std::string key = Reader::join(path, "phong_exponents");
        const toml::array *a = e->as_array();
        if (!a) rd.fail(e->source(), key, "expected an array of integer Phong exponents in [1, " +
                                              std::to_string(kSceneMaxPhongExponent) + "]");
        for (size_t i = 0; i < a->size(); ++i) {
            const toml::node &x = *a->get(i);
            const std::string at = key + "[" + std::to_string(i) + "]";
            if (!x.is_integer()) rd.fail(x.source(), at, "expected " + expect);
            const int64_t v = x.value<int64_t>().value_or(0);
            if (v < 1 || v > kSceneMaxPhongExponent)
                rd.fail(x.source(), at, "expected " + expect + ", got " + std::to_string(v));
            if (std::find(s.phong_exponents.begin(), s.phong_exponents.end(), v) != s.phong_exponents.end())
                rd.fail(x.source(), at, "expected exponents no other entry has, got " + std::to_string(v) + " twice");
            s.phong_exponents.push_back(static_cast<int>(v));
        }
        std::sort(s.phong_exponents.begin(), s.phong_exponents.end());
    }
    if (!s.diffuse && s.phong_exponents.empty())
        rd.fail(t.source(), Reader::join(path, "diffuse"),
                "expected diffuse = true and/or a non-empty phong_exponents (surfaces that reflect nothing need no table)");
    const toml::node *d = t.get("light_distance_m");
    if (!d) rd.fail(t.source(), Reader::join(path, "light_distance_m"),
                    "expected [min, max] in m, the distance from a lit surface point to a light (missing)");
    s.light_distance_m = rd.range(*d, Reader::join(path, "light_distance_m"));
    return s;
}

SceneMedium read_medium(const Reader &rd, const toml::table &t, const std::string &path, double relative_error) {
    rd.only_keys(t, path,
                 {"name", "sigma_s_per_m", "sigma_a_per_m", "phase_g", "viewer_inside", "thick", "thickness_m",
                  "relative_error", "surfaces"});
    SceneMedium m;
    m.line = static_cast<int>(t.source().begin.line);
    m.name = rd.string(t, "name", path, true, "");
    m.sigma_s_rgb_per_m = rd.number_or_rgb(t, "sigma_s_per_m", path, kSceneMaxSigma_per_m, kSigmaOrRgbExpected);
    m.sigma_a_rgb_per_m = rd.number_or_rgb(t, "sigma_a_per_m", path, kSceneMaxSigma_per_m, kSigmaOrRgbExpected);
    auto grey = [](const std::array<double, 3> &c) { return c[0] == c[1] && c[1] == c[2]; };
    m.coloured = !grey(m.sigma_s_rgb_per_m) || !grey(m.sigma_a_rgb_per_m);
    m.sigma_s_per_m = std::max({m.sigma_s_rgb_per_m[0], m.sigma_s_rgb_per_m[1], m.sigma_s_rgb_per_m[2]});
    m.sigma_a_per_m = std::max({m.sigma_a_rgb_per_m[0], m.sigma_a_rgb_per_m[1], m.sigma_a_rgb_per_m[2]});
    m.phase_g = rd.number(t, "phase_g", path, false, 0.0, -kSceneMaxPhaseG, false, kSceneMaxPhaseG, kPhaseGExpected);
    m.viewer_inside = rd.boolean(t, "viewer_inside", path, true, false);
    m.relative_error = rd.number(t, "relative_error", path, false, relative_error, kSceneMinRelativeError, false, 0.5,
                                 kRelativeErrorExpected);
    m.thick = rd.boolean(t, "thick", path, false, false);
    if (const toml::node *n = t.get("thickness_m")) {
        m.thickness_m = rd.range(*n, Reader::join(path, "thickness_m"));
        m.has_thickness = true;
    }
    if (m.viewer_inside && (m.thick || m.has_thickness)) {
        const char *key = m.has_thickness ? "thickness_m" : "thick";
        rd.fail(t.get(key)->source(), Reader::join(path, key),
                "expected no such key: it applies only to media seen from outside (viewer_inside = false)");
    }
    if (const toml::node *n = t.get("surfaces")) {
        if (!m.viewer_inside)
            rd.fail(n->source(), Reader::join(path, "surfaces"),
                    "expected no such key: lit surfaces apply only to a medium the viewer is inside (viewer_inside = true)");
        m.surfaces = read_surfaces(rd, *n, Reader::join(path, "surfaces"));
        m.has_surfaces = true;
    }
    if (!m.viewer_inside && !m.thick && !m.has_thickness)
        rd.fail(t.source(), Reader::join(path, "thickness_m"),
                "expected thick = true and/or thickness_m = [min, max] for a medium seen from outside (missing)");
    return m;
}

// A spot's cone (docs/SPOT.md): direction = [x, y, z] (non-zero; light → lit points),
// outer_angle_deg in [0, 180], inner_angle_deg in [0, outer] (default: the outer, a hard cone).
void read_spot_cone(const Reader &rd, const toml::table &t, const std::string &path, SceneLight &l) {
    const std::string key = Reader::join(path, "direction");
    const toml::node *n = t.get("direction");
    if (!n) rd.fail(t.source(), key, "expected [x, y, z], the spot's axis (missing)");
    const toml::array *a = n->as_array();
    if (!a || a->size() != 3) rd.fail(n->source(), key, "expected [x, y, z], the spot's axis");
    double length2 = 0;
    for (size_t i = 0; i < 3; ++i) {
        const std::optional<double> v = a->get(i)->value<double>();
        if (!v || !std::isfinite(*v)) rd.fail(a->get(i)->source(), key + "[" + std::to_string(i) + "]", "expected a finite number");
        l.spot_direction[i] = *v;
        length2 += *v * *v;
    }
    if (!(length2 > 0.0)) rd.fail(n->source(), key, "expected a non-zero vector");
    l.outer_angle_deg = rd.number(t, "outer_angle_deg", path, true, 0, 0.0, false, 180.0, "a number in [0, 180] (degrees)");
    l.inner_angle_deg = rd.number(t, "inner_angle_deg", path, false, l.outer_angle_deg, 0.0, false, l.outer_angle_deg,
                                  "a number in [0, outer_angle_deg] (degrees)");
}

SceneLight read_light(const Reader &rd, const toml::table &t, const std::string &path) {
    SceneLight l;
    l.line = static_cast<int>(t.source().begin.line);
    const std::string type = rd.string(t, "type", path, true, "", {"point", "spot", "directional"});
    l.type = type == "directional" ? LightType::Directional : LightType::Point;
    l.spot = type == "spot";
    if (l.spot) {
        rd.only_keys(t, path, {"name", "type", "intensity_W_per_sr", "distance_m", "media", "direction",
                               "outer_angle_deg", "inner_angle_deg"});
        read_spot_cone(rd, t, path, l);
    } else if (l.type == LightType::Point) {
        rd.only_keys(t, path, {"name", "type", "intensity_W_per_sr", "distance_m", "media"});
    }
    if (l.type == LightType::Point) {
        l.intensity_W_per_sr =
            rd.number(t, "intensity_W_per_sr", path, true, 0, 0.0, true, kSceneMaxIntensity, "a number in (0, 1e30] (W/sr)");
        const toml::node *d = t.get("distance_m");
        if (!d) rd.fail(t.source(), Reader::join(path, "distance_m"), "expected [min, max] in m (missing)");
        l.distance_m = rd.range(*d, Reader::join(path, "distance_m"));
    } else {
        rd.only_keys(t, path, {"name", "type", "irradiance_W_per_m2", "media"});
        l.irradiance_W_per_m2 =
            rd.number(t, "irradiance_W_per_m2", path, false, 1.0, 0.0, true, kSceneMaxIntensity,
                      "a number in (0, 1e30] (W/m^2)");
    }
    l.name = rd.string(t, "name", path, true, "");
    if (const toml::node *n = t.get("media")) {
        const std::string key = Reader::join(path, "media");
        const toml::array *a = n->as_array();
        if (!a || a->empty()) rd.fail(n->source(), key, "expected a non-empty array of medium names");
        for (size_t i = 0; i < a->size(); ++i) {
            const toml::node &e = *a->get(i);
            if (!e.is_string()) rd.fail(e.source(), key + "[" + std::to_string(i) + "]", "expected a medium name (string)");
            l.media.push_back(e.value<std::string>().value_or(""));
        }
    }
    return l;
}

// Checks across tables: unique names, lights naming media that exist.
void check_names(const Reader &rd, const toml::table &root, const Scene &s) {
    std::set<std::string> media;
    for (size_t i = 0; i < s.media.size(); ++i) {
        if (!media.insert(s.media[i].name).second) {
            const toml::node &n = *root["medium"][i]["name"].node();
            rd.fail(n.source(), "medium[" + std::to_string(i) + "].name", "expected a name no other medium has");
        }
    }
    std::set<std::string> lights;
    for (size_t i = 0; i < s.lights.size(); ++i) {
        const std::string path = "light[" + std::to_string(i) + "]";
        if (!lights.insert(s.lights[i].name).second)
            rd.fail(root["light"][i]["name"].node()->source(), path + ".name", "expected a name no other light has");
        for (size_t k = 0; k < s.lights[i].media.size(); ++k)
            if (!media.count(s.lights[i].media[k]))
                rd.fail(root["light"][i]["media"][k].node()->source(), path + ".media[" + std::to_string(k) + "]",
                        "expected the name of a [[medium]], got '" + s.lights[i].media[k] + "'");
    }
}

// Optical depths a table can serve (media that scatter): sigma_t times a point light's largest distance (for
// every medium it lights) or a slab's largest thickness at most kSceneMaxOpticalDepth.
void check_optical_depths(const Reader &rd, const toml::table &root, const Scene &s) {
    auto too_deep = [](double sigma_t, double length) { return sigma_t * length > kSceneMaxOpticalDepth; };
    auto what = [](const SceneMedium &m, double length) {
        std::ostringstream msg;
        msg.precision(6);
        msg << "expected sigma_t * length <= 1e4 optical depths with medium '" << m.name << "' (sigma_t = "
            << m.sigma_t_per_m() << " 1/m), got " << m.sigma_t_per_m() * length
            << " (the light would be attenuated below the smallest double)";
        return msg.str();
    };
    for (size_t i = 0; i < s.media.size(); ++i) {
        const SceneMedium &m = s.media[i];
        if (m.sigma_s_per_m > 0.0 && m.has_thickness && too_deep(m.sigma_t_per_m(), m.thickness_m.max))
            rd.fail(root["medium"][i]["thickness_m"].node()->source(), "medium[" + std::to_string(i) + "].thickness_m",
                    what(m, m.thickness_m.max));
        if (m.sigma_s_per_m > 0.0 && m.has_surfaces && too_deep(m.sigma_t_per_m(), m.surfaces.light_distance_m.max))
            rd.fail(root["medium"][i]["surfaces"]["light_distance_m"].node()->source(),
                    "medium[" + std::to_string(i) + "].surfaces.light_distance_m",
                    what(m, m.surfaces.light_distance_m.max));
    }
    for (size_t i = 0; i < s.lights.size(); ++i) {
        const SceneLight &l = s.lights[i];
        if (l.type != LightType::Point) continue;
        for (const SceneMedium &m : s.media)
            if (m.sigma_s_per_m > 0.0 && Scene::lights_medium(l, m) && too_deep(m.sigma_t_per_m(), l.distance_m.max))
                rd.fail(root["light"][i]["distance_m"].node()->source(), "light[" + std::to_string(i) + "].distance_m",
                        what(m, l.distance_m.max));
    }
}

// [[medium]] / [[light]]: an array of tables (one table alone is accepted too).
template <class Item, class ReadFn>
std::vector<Item> read_array(const Reader &rd, const toml::table &root, const char *key, ReadFn read) {
    std::vector<Item> out;
    const toml::node *n = root.get(key);
    if (!n) return out;
    const toml::array *a = n->as_array();
    if (!a) rd.fail(n->source(), key, std::string("expected an array of tables ([[") + key + "]])");
    for (size_t i = 0; i < a->size(); ++i) {
        const toml::node &e = *a->get(i);
        const std::string path = std::string(key) + "[" + std::to_string(i) + "]";
        if (!e.is_table()) rd.fail(e.source(), path, std::string("expected a table ([[") + key + "]])");
        out.push_back(read(rd, *e.as_table(), path));
    }
    return out;
}

} // namespace

bool Scene::lights_medium(const SceneLight &light, const SceneMedium &medium) {
    return light.media.empty() || std::find(light.media.begin(), light.media.end(), medium.name) != light.media.end();
}

namespace {

// What toml++ must not see: text that is not valid UTF-8, and a non-ASCII character outside
// strings and comments (TOML's keys, values and whitespace are ASCII there). toml++ 3.x
// classifies such a character with a table that reaches an unreachable branch for some
// code points (U+00A1–U+0499, U+2CDE–U+30D7, U+FBC6–U+FEFE; undefined behaviour in a release
// build, found by tests/fuzz/fuzz_inputs.cpp), so it is refused here first, as the syntax
// error it is. Throws SceneError with file:line:column.
void check_scene_text(const std::string &text, const std::string &source) {
    enum { Normal, Comment, Basic, Literal, MultiBasic, MultiLiteral } state = Normal;
    size_t line = 1, column = 1;
    auto fail = [&](const char *what) {
        std::ostringstream msg;
        msg << source << ":" << line << ":" << column << ": syntax error: " << what;
        throw SceneError(msg.str());
    };
    auto starts = [&](size_t i, const char *s) { return text.compare(i, std::strlen(s), s) == 0; };
    auto escape_at = [&](size_t i) { // a backslash escaping the next ASCII character (not a line end)
        return text[i] == '\\' && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) < 0x80 &&
               text[i + 1] != '\n';
    };
    const size_t n = text.size();
    for (size_t i = 0; i < n;) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c >= 0x80) {
            const size_t len = utf8_sequence_length(text, i);
            if (len == 0) fail("not valid UTF-8");
            if (state == Normal) fail("a non-ASCII character outside a string or comment (expected ASCII keys and values)");
            i += len;
            ++column;
            continue;
        }
        size_t step = 1;
        switch (state) {
        case Normal:
            if (c == '#') {
                state = Comment;
            } else if (starts(i, "\"\"\"")) {
                state = MultiBasic;
                step = 3;
            } else if (starts(i, "'''")) {
                state = MultiLiteral;
                step = 3;
            } else if (c == '"') {
                state = Basic;
            } else if (c == '\'') {
                state = Literal;
            }
            break;
        case Comment:
            if (c == '\n') state = Normal;
            break;
        case Basic:
            if (escape_at(i)) step = 2;
            else if (c == '"' || c == '\n') state = Normal;
            break;
        case Literal:
            if (c == '\'' || c == '\n') state = Normal;
            break;
        case MultiBasic:
            if (escape_at(i)) {
                step = 2;
            } else if (starts(i, "\"\"\"")) {
                state = Normal;
                step = 3;
                while (i + step < n && step < 5 && text[i + step] == '"') ++step; // up to two quotes of content
            }
            break;
        case MultiLiteral:
            if (starts(i, "'''")) {
                state = Normal;
                step = 3;
                while (i + step < n && step < 5 && text[i + step] == '\'') ++step;
            }
            break;
        }
        for (size_t k = 0; k < step; ++k) {
            if (text[i + k] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        i += step;
    }
}

} // namespace

Scene parse_scene(const std::string &text, const std::string &source) {
    check_scene_text(text, source);
    toml::table root;
    try {
        root = toml::parse(text, source);
    } catch (const toml::parse_error &e) {
        std::ostringstream msg;
        msg << source << ":" << e.source().begin.line << ":" << e.source().begin.column
            << ": syntax error: " << e.description();
        throw SceneError(msg.str());
    }
    const Reader rd(source);
    Scene s;
    s.source = source;
    s.text = text;
    rd.only_keys(root, "", {"name", "accuracy", "view", "output", "medium", "light"});
    s.name = rd.string(root, "name", "", false, "");
    if (const toml::table *a = rd.table(root, "accuracy", "")) {
        rd.only_keys(*a, "accuracy", {"relative_error", "max_table_MiB"});
        s.relative_error = rd.number(*a, "relative_error", "accuracy", false, s.relative_error, kSceneMinRelativeError,
                                     false, 0.5, kRelativeErrorExpected);
        s.max_table_MiB = rd.number(*a, "max_table_MiB", "accuracy", false, s.max_table_MiB, kSceneMinTableMiB, false,
                                    4096.0, "a size in MiB in [0.01, 4096] (the smallest table takes ~1 KiB)");
    }
    if (const toml::table *v = rd.table(root, "view", "")) {
        rd.only_keys(*v, "view", {"max_view_angle_deg", "max_light_angle_deg"});
        s.view.max_view_angle_deg = rd.number(*v, "max_view_angle_deg", "view", false, s.view.max_view_angle_deg, 0.0,
                                              true, 89.9, "an angle in degrees in (0, 89.9]");
        s.view.max_light_angle_deg = rd.number(*v, "max_light_angle_deg", "view", false, s.view.max_light_angle_deg,
                                               0.0, true, 90.0, "an angle in degrees in (0, 90]");
    }
    if (const toml::table *o = rd.table(root, "output", "")) {
        rd.only_keys(*o, "output", {"directory", "format", "storage"});
        s.output.directory = rd.string(*o, "directory", "output", false, s.output.directory);
        s.output.format =
            rd.string(*o, "format", "output", false, s.output.format, {"bin", "exr", "ktx2", "both", "all"});
        s.output.storage = rd.string(*o, "storage", "output", false, s.output.storage, {"f16", "f32", "f64"});
        if ((s.output.format == "exr" || s.output.format == "ktx2") && s.output.storage == "f64")
            rd.fail(o->get("storage")->source(), "output.storage",
                    "expected 'f16' or 'f32' with format '" + s.output.format + "' (" +
                        (s.output.format == "exr" ? "EXR" : "KTX2") +
                        " holds no f64; f64 needs format 'bin', 'both' or 'all')");
    }
    s.media = read_array<SceneMedium>(rd, root, "medium", [&](const Reader &r, const toml::table &t, const std::string &p) {
        return read_medium(r, t, p, s.relative_error);
    });
    s.lights = read_array<SceneLight>(rd, root, "light", read_light);
    check_names(rd, root, s);
    check_optical_depths(rd, root, s);
    return s;
}

Scene load_scene_file(const std::string &path) {
    // A regular file of at most kMaxSceneBytes (what a table's provenance can carry), checked
    // before reading: a FIFO, /dev/zero or a directory is refused without blocking.
    std::vector<uint8_t> bytes;
    try {
        bytes = detail::read_file(path, kMaxSceneBytes, "a scene file (TOML)");
    } catch (const LoadError &e) {
        throw SceneError(e.what());
    }
    return parse_scene(std::string(bytes.begin(), bytes.end()), path);
}

Scene default_scene() {
    for (std::size_t i = 0; i < embedded::kSceneFileCount; ++i)
        if (std::string(embedded::kSceneFiles[i].name) == "default.toml")
            return parse_scene(embedded::kSceneFiles[i].contents, "<default scene>");
    throw std::logic_error("the default scene is not embedded in this binary");
}

} // namespace scatterlut
