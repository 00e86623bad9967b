// The WebGPU test's cases (tests/shaders/webgpu_snippets.mjs, ctest WebGPUSnippets): what a GLSL
// shader test runs -- its table, its per-query body (the GLSL subset, translated to WGSL by
// tables/shaders/wgsl/slut_wgsl.py harness), its parameter block, its queries, their C++ references
// and its tolerances -- written as JSON, so that the WGSL snippets run on exactly the GLSL
// tests' queries against exactly their references and tolerances.
//
// A shader test registers its cases with SLUT_WGSL_CASES(function): run with the environment
// variable SLUT_WGSL_CASES=FILE, the test binary writes FILE and exits before any test runs.
//
// Per case set: the snippet (scatterlut_<snippet>[_<tier>].wgsl), the tiers to run and per tier
// and query the tolerance a + b * w, w the filter weight error the WebGPU test measures on its
// adapter (b = 0 where no filtered fetch is involved); the table as a 2-D or 3-D r32float
// texture; the uniform block's fields (params_decl, the GLSL test's, which WGSL lays out as
// std140 does for these fields) and bytes; the query records (query_floats floats each); per
// query its label (category) and reference (a number, or "inf" / "-inf" / "nan").
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace wgsl_cases {

struct Tier {
    std::string name;                       // "" (no tier), "fast", "accurate"
    std::vector<double> tol;                // per query: a
    std::vector<double> tol_per_weight_error; // per query: b (empty: 0)
};

struct CaseSet {
    std::string name;    // for the printout, e.g. "nearlight E4"
    std::string snippet; // airlight, airlight_hg, nearlight, nearlight_hg, surface
    std::string texture = "2d";
    int width = 0, height = 0, depth = 1;
    std::vector<float> texels;
    std::string params_decl; // the GLSL uniform block's fields
    std::vector<unsigned char> params; // their std140 bytes
    std::string body;        // float test_eval(int i) and its helpers, in the GLSL subset
    int query_floats = 0;
    std::vector<float> queries;
    std::vector<std::string> labels;
    std::vector<double> reference;
    std::vector<Tier> tiers;
    // Not "": why this set is not run on SwiftShader (the WebGPU test says so, and runs it
    // with --slow or on any other adapter).
    std::string slow_on_swiftshader;
};

template <class T>
std::vector<unsigned char> bytes_of(const T &value) {
    std::vector<unsigned char> b(sizeof value);
    std::memcpy(b.data(), &value, sizeof value);
    return b;
}

inline std::string base64(const void *data, size_t size) {
    static const char *k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const auto *p = static_cast<const unsigned char *>(data);
    std::string out;
    out.reserve((size + 2) / 3 * 4);
    for (size_t i = 0; i < size; i += 3) {
        const unsigned v = (p[i] << 16) | ((i + 1 < size ? p[i + 1] : 0) << 8) | (i + 2 < size ? p[i + 2] : 0);
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < size ? k[(v >> 6) & 63] : '=';
        out += i + 2 < size ? k[v & 63] : '=';
    }
    return out;
}

inline nlohmann::json number(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    return x;
}

inline nlohmann::json to_json(const CaseSet &c) {
    const size_t n = c.labels.size();
    if (c.reference.size() != n || c.queries.size() != n * static_cast<size_t>(c.query_floats))
        throw std::runtime_error("wgsl_cases: " + c.name + ": queries, labels and references differ in number");
    nlohmann::json j;
    j["name"] = c.name;
    j["snippet"] = c.snippet;
    j["texture"] = c.texture;
    j["width"] = c.width;
    j["height"] = c.height;
    j["depth"] = c.depth;
    if (c.texels.size() != static_cast<size_t>(c.width) * c.height * c.depth)
        throw std::runtime_error("wgsl_cases: " + c.name + ": texel count differs from the texture size");
    j["texels"] = base64(c.texels.data(), c.texels.size() * sizeof(float));
    j["params_decl"] = c.params_decl;
    j["params"] = base64(c.params.data(), c.params.size());
    j["body"] = c.body;
    j["query_floats"] = c.query_floats;
    j["queries"] = base64(c.queries.data(), c.queries.size() * sizeof(float));
    j["labels"] = c.labels;
    nlohmann::json ref = nlohmann::json::array();
    for (double r : c.reference) ref.push_back(number(r));
    j["reference"] = ref;
    nlohmann::json tiers = nlohmann::json::array();
    for (const Tier &t : c.tiers) {
        if (t.tol.size() != n || !(t.tol_per_weight_error.empty() || t.tol_per_weight_error.size() == n))
            throw std::runtime_error("wgsl_cases: " + c.name + ": tier '" + t.name + "' has no tolerance per query");
        nlohmann::json tj;
        tj["name"] = t.name;
        tj["tol"] = t.tol;
        tj["tol_per_weight_error"] = t.tol_per_weight_error.empty() ? std::vector<double>(n, 0.0) : t.tol_per_weight_error;
        tiers.push_back(tj);
    }
    j["tiers"] = tiers;
    j["slow_on_swiftshader"] = c.slow_on_swiftshader;
    return j;
}

inline void write(const std::string &path, const std::vector<CaseSet> &sets) {
    nlohmann::json all = nlohmann::json::array();
    for (const CaseSet &c : sets) all.push_back(to_json(c));
    std::ofstream out(path, std::ios::binary);
    out << all.dump();
    if (!out) throw std::runtime_error("wgsl_cases: cannot write " + path);
}

// The environment that writes the cases instead of running the tests (see the top).
class Writer : public ::testing::Environment {
public:
    explicit Writer(std::function<std::vector<CaseSet>()> make) : make_(std::move(make)) {}
    void SetUp() override {
        const char *path = std::getenv("SLUT_WGSL_CASES");
        if (!path || !*path) return;
        try {
            const std::vector<CaseSet> sets = make_();
            write(path, sets);
            size_t queries = 0;
            for (const CaseSet &c : sets) queries += c.labels.size();
            std::printf("wrote %zu case sets, %zu queries, to %s\n", sets.size(), queries, path);
            std::fflush(stdout);
            std::exit(0);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "writing the WebGPU cases to %s failed: %s\n", path, e.what());
            std::exit(1);
        }
    }

private:
    std::function<std::vector<CaseSet>()> make_;
};

} // namespace wgsl_cases

// In a shader test's .cpp, at namespace scope: SLUT_WGSL_CASES(function returning the case sets).
#define SLUT_WGSL_CASES(make) \
    static ::testing::Environment *const slut_wgsl_cases_environment = \
        ::testing::AddGlobalTestEnvironment(new ::wgsl_cases::Writer(make))
