// scatterlut runtime — an in-memory table: axes, channels, values and the metadata
// that makes a file self-describing. No OpenCL, no CLI; shared by the generator,
// the validator and engines.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

extern "C" {
#include "slut_axes.h"
}

namespace scatterlut {

// Format version written by this library. Readers refuse another major version and
// read newer minor versions (ignoring fields they do not know).
inline constexpr uint32_t kFormatMajor = 1;
inline constexpr uint32_t kFormatMinor = 1;

// Most axes a table may have (the sampler keeps per-axis state in fixed arrays of this
// size; the file formats use the same bound).
inline constexpr size_t kMaxAxes = 8;

// Table kinds. Each has a quantity-definition version: bump it when the meaning of
// the stored values changes (a reader must not silently mix definitions).
inline constexpr const char *kKindAirlightF = "airlight_F";
inline constexpr uint32_t kAirlightFQuantityVersion = 1;
// Ĥ(x_m, x_t): the airlight's tail normalised, on rational axes (kernels/slut_airlight_rational.h;
// the GPU snippets' fast tier; AirlightRationalTable, scatterlut/airlight_rational.hpp).
inline constexpr const char *kKindAirlightRational = "airlight_rational";
inline constexpr uint32_t kAirlightRationalQuantityVersion = 1;
inline constexpr const char *kKindNearLightE3 = "near_light_E3"; // E(T, g, r), S = ∞
inline constexpr const char *kKindNearLightE4 = "near_light_E4"; // E(T, g, r, S) on axes (T, g, r, q)
// 2: E4 stores ln(E/B) on the slab axis q (warp nl_qodds); 1 stored ln E on a log S axis.
inline constexpr uint32_t kNearLightEQuantityVersion = 2;
// The stored logarithms' physical range, which AirlightTable and NearLightTable check at
// load (naming the node): ln G̃ ≤ 0, ln E ≤ 0, ln(E/B) ≤ T, each within kLnRoundingSlack
// (storage rounding), and none below kMinStoredLn (e^{−1e6}: no double is left).
inline constexpr double kLnRoundingSlack = 1e-3;
inline constexpr double kMinStoredLn = -1e6;

enum class Storage : uint32_t { F16 = 1, F32 = 2, F64 = 3 };
const char *to_string(Storage s);
bool storage_from_string(const std::string &name, Storage *out);
size_t storage_bytes(Storage s);

// How a channel's stored number relates to the quantity.
enum class Encoding : uint32_t {
    Linear = 0, // stored = quantity
    Log = 1,    // stored = ln(quantity); quantity = exp(stored)
};
const char *to_string(Encoding e);
bool encoding_from_string(const std::string &name, Encoding *out);

const char *warp_name(int warp); // "linear", "log", "log1p", "asinh_cot", "sqrt1p", "loglin", "nl_qodds", "asinh_cot_peak"
bool warp_from_name(const std::string &name, int *out);

struct Axis {
    std::string name;      // parameter name, e.g. "u", "w" (w = π/2 − v)
    std::string meaning;   // one line, e.g. "optical distance σt·D·sin γ"
    slut_axis map{};       // min, max, scale, warp, count: the shared maps
};

struct Channel {
    std::string name;      // e.g. "ln_Gs"
    std::string meaning;   // one line
    Encoding encoding = Encoding::Linear;
};

// Measured accuracy, all relative errors on the quantity (not on its encoding).
struct Accuracy {
    double integration_max_rel = -1; // nodes vs an independent high-accuracy pass
    double sampling_max_rel = -1;    // interpolated vs exact at off-node points
    double sampling_p99_rel = -1;
    double sampling_median_rel = -1;
    double storage_max_rel = -1;     // rounding to the storage type (f16/f32/f64)
    uint64_t sampling_points = 0;
    std::string sampling_domain;     // where the sampling error was measured
};

struct Provenance {
    std::string generator_version;
    std::string command_line;
    std::string scene;   // the scene text (TOML) the table was planned from, or ""
    std::string device;  // OpenCL platform / device / driver
    std::string created_by = "scatterlut";
};

struct Table {
    std::string kind;                 // kKindAirlightF, ...
    uint32_t quantity_version = 0;
    std::vector<Axis> axes;           // axis 0 varies fastest in `values`
    std::vector<Channel> channels;    // channel varies fastest of all
    Storage storage = Storage::F32;
    // values[(((i_{n-1}·c_{n-2} + …)·c_0 + i_0)·channels + ch)] as stored (encoded),
    // widened to double; after a round trip through f16/f32 they are the rounded values.
    std::vector<double> values;
    Accuracy accuracy;
    Provenance provenance;
    std::map<std::string, std::string> extra; // free key/value metadata (kept on round trip)

    size_t node_count() const;              // product of axis counts
    size_t index(const size_t *node) const; // flat index of channel 0 at a node
    // Throws std::invalid_argument with a message if axes/channels/values disagree.
    void check_consistent() const;
};

} // namespace scatterlut
