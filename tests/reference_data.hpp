// Loads the 30-digit mpmath references of tests/reference (SLUT_REFERENCE_DIR; conventions
// and how they were computed in tests/reference/README.md).
// Values are decimal strings; they are parsed as long double so a test can state
// its own tolerance without the loader adding error. A missing or malformed file
// fails the calling test with a clear message (never an empty, silently passing list).
#pragma once

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace slut_test {

inline std::string reference_dir() { return SLUT_REFERENCE_DIR; }

inline nlohmann::json load_json(const std::string &name) {
    const std::string path = reference_dir() + "/" + name;
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open reference file " + path);
    return nlohmann::json::parse(in);
}

// A number that may be a JSON number or a decimal string ("inf" allowed).
inline long double ref_number(const nlohmann::json &j) {
    if (j.is_number()) return j.get<long double>();
    if (j.is_string()) {
        const std::string s = j.get<std::string>();
        if (s == "inf") return std::numeric_limits<long double>::infinity();
        char *end = nullptr;
        long double v = std::strtold(s.c_str(), &end);
        if (end == s.c_str()) throw std::runtime_error("not a number in reference: " + s);
        return v; // values below long double range parse as 0 (e.g. "3.6e-7092591")
    }
    throw std::runtime_error("reference value is neither number nor string: " + j.dump());
}

struct FRef { double u, v; long double F, tail; };
struct NRef { double T, g, r, S; long double N, H, E; }; // S = +inf for a thick medium
struct AirlightRef { double sigma_s, sigma_a, intensity, distance, gamma, length; long double L; };
struct NearLightRef {
    double sigma_s, sigma_a, intensity;
    double normal[3], eye_dir[3], light_pos[3];
    double length; // +inf = thick
    long double L;
};

inline std::vector<FRef> load_F_refs() {
    std::vector<FRef> out;
    const nlohmann::json file = load_json("F_ref.json"); // outlives the loop (no dangling temporary)
    for (const auto &p : file.at("points"))
        out.push_back({p.at("u").get<double>(), p.at("v").get<double>(), ref_number(p.at("F")), ref_number(p.at("tail"))});
    if (out.empty()) throw std::runtime_error("F_ref.json has no points");
    return out;
}

inline std::vector<NRef> load_N_refs() {
    std::vector<NRef> out;
    const nlohmann::json file = load_json("N_ref.json");
    for (const auto &p : file.at("points"))
        out.push_back({p.at("T").get<double>(), p.at("g").get<double>(), p.at("r").get<double>(),
                       (double)ref_number(p.at("S")), ref_number(p.at("N")), ref_number(p.at("H")), ref_number(p.at("E"))});
    if (out.empty()) throw std::runtime_error("N_ref.json has no points");
    return out;
}

inline std::vector<AirlightRef> load_airlight_refs() {
    std::vector<AirlightRef> out;
    const nlohmann::json file = load_json("physical_ref.json");
    for (const auto &c : file.at("cases")) {
        if (c.at("quantity") != "airlight") continue;
        out.push_back({c.at("sigma_s").get<double>(), c.at("sigma_a").get<double>(), c.at("intensity").get<double>(),
                       c.at("distance").get<double>(), c.at("gamma").get<double>(), c.at("length").get<double>(),
                       ref_number(c.at("L"))});
    }
    if (out.empty()) throw std::runtime_error("physical_ref.json has no airlight cases");
    return out;
}

inline std::vector<NearLightRef> load_near_light_refs() {
    std::vector<NearLightRef> out;
    const nlohmann::json file = load_json("physical_ref.json");
    for (const auto &c : file.at("cases")) {
        if (c.at("quantity") != "near_light") continue;
        NearLightRef r{};
        r.sigma_s = c.at("sigma_s").get<double>();
        r.sigma_a = c.at("sigma_a").get<double>();
        r.intensity = c.at("intensity").get<double>();
        for (int k = 0; k < 3; ++k) {
            r.normal[k] = c.at("normal").at(k).get<double>();
            r.eye_dir[k] = c.at("eye_dir").at(k).get<double>();
            r.light_pos[k] = c.at("light_pos").at(k).get<double>();
        }
        r.length = (double)ref_number(c.at("length"));
        r.L = ref_number(c.at("L"));
        out.push_back(r);
    }
    if (out.empty()) throw std::runtime_error("physical_ref.json has no near_light cases");
    return out;
}

// Relative error |a − b| / |b|, with b = 0 compared absolutely.
inline double rel_err(long double a, long double b) {
    if (b == 0) return (double)std::fabs(a);
    return (double)(std::fabs(a - b) / std::fabs(b));
}

} // namespace slut_test
