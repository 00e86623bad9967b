// render_fog — a foggy street with glowing lamps and a lit translucent slab, rendered
// twice: from the scatterlut tables (AirlightTable, NearLightTable) and from the exact
// quadratures (airlight_radiance_exact, near_light_radiance_exact). Writes table.png and
// exact.png (identical tone mapping) and prints the PSNR between them and the time each
// image took. Exits 1 if the 8-bit PSNR is below 45 dB.
//
// Given an anisotropic airlight table of g = 0.85 (kind airlight_Fg, from
// `scatterlut generate --scene examples/scenes/fog_forward.toml`), it renders the street a
// second time in forward-scattering, coloured fog (Henyey–Greenstein phase, per-channel
// coefficients): the lamps' glow from that one table per channel (AirlightHgTable::radiance_rgb)
// and exactly (airlight_radiance_exact_rgb), written to table_hg.png and exact_hg.png, with
// the same PSNR check.
//
//   render_fog out/airlight_F.slut out/near_light_E3.slut out_dir [out_fwd/airlight_Fg_g0.85.slut]
//
// Links only scatterlut::tables and the project's small internal PNG encoder
// (tables/png, stored deflate blocks: no zlib/libpng dependency).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/anisotropic.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/nearlight.hpp"
#include "png_writer.hpp"

namespace {

constexpr int kWidth = 480, kHeight = 270;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Vec3 {
    double x, y, z;
};
Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 normalize(Vec3 a) { return (1.0 / std::sqrt(dot(a, a))) * a; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

struct Light {
    Vec3 pos;       // m
    double I0;      // W/sr
    Vec3 color;     // relative spectral tint (grey medium: radiance × color)
};

// --- scene (metres, 1/m; y up, camera looking down −z) --------------------------------
const Vec3 kEye{0.0, 1.7, 0.0};
const Vec3 kTarget{0.0, 2.4, -30.0};
constexpr double kFovY = 50.0 * 3.14159265358979323846 / 180.0;

// Fog around the street.
constexpr double kFogSigmaS = 0.04, kFogSigmaA = 0.01;
// The second picture's fog: the two media of examples/scenes/fog_forward.toml in one volume,
// the droplet fog (σ_s = 0.05, σ_a = 0.002 per m, g = 0.85) and the blue haze (σ_s = [0.004,
// 0.007, 0.012], σ_a = 0.001 per m), scattering with the fog's phase g = 0.85 throughout (the
// haze's own g = 0.3 replaced by it: the fog carries 81–93 % of σ_s). The same medium in the
// table and the exact picture.
constexpr double kHgPhaseG = 0.85;
const scatterlut::Rgb kHgSigmaS{0.054, 0.057, 0.062}; // 1/m per channel (r, g, b)
const scatterlut::Rgb kHgSigmaA{0.003, 0.003, 0.003};
// Translucent slab (a 2 m wax-like block face; σ in 1/m, scaled so that σ_t·l spans the
// table's T range across the face: the glow around the small lamp falls off visibly).
constexpr double kSlabSigmaS = 5.0, kSlabSigmaA = 0.2;
const Vec3 kSlabColor{1.0, 0.5, 0.25};
// Slab front face: plane z = kSlabZ, x ∈ [kSlabX0, kSlabX1], y ∈ [0, kSlabH], normal +z.
constexpr double kSlabZ = -9.0, kSlabX0 = 1.2, kSlabX1 = 3.2, kSlabH = 2.0;
// The far wall closing the street; rays above it go to the sky (infinite length).
constexpr double kWallZ = -90.0, kWallH = 14.0;

const std::vector<Light> kLights = {
    {{-3.5, 5.0, -12.0}, 300.0, {1.0, 0.72, 0.38}},  // sodium lamps along the street
    {{3.8, 5.0, -26.0}, 300.0, {1.0, 0.72, 0.38}},
    {{-3.8, 5.0, -45.0}, 300.0, {1.0, 0.72, 0.38}},
    {{3.8, 5.0, -70.0}, 300.0, {1.0, 0.72, 0.38}},
    {{2.0, 1.2, -8.6}, 40.0, {0.85, 0.9, 1.0}},       // small lamp 0.4 m in front of the slab
    {{-2.0, 4.0, 3.0}, 200.0, {1.0, 0.72, 0.38}},    // behind the camera, out of view
};

struct Hit {
    double s = kInf;   // ray length in the fog
    bool slab = false; // hit the slab face
};

Hit trace(Vec3 o, Vec3 d) {
    Hit h;
    if (d.y < 0) { // ground y = 0
        double t = -o.y / d.y;
        if (t < h.s) h.s = t;
    }
    if (d.z < 0) {
        double t = (kWallZ - o.z) / d.z;
        Vec3 p = o + t * d;
        if (t < h.s && p.y <= kWallH) h.s = t;
        t = (kSlabZ - o.z) / d.z;
        p = o + t * d;
        if (t < h.s && p.x >= kSlabX0 && p.x <= kSlabX1 && p.y >= 0 && p.y <= kSlabH) {
            h.s = t;
            h.slab = true;
        }
    }
    return h;
}

// The fog's coefficients per channel, 1/m.
struct Medium {
    scatterlut::Rgb sigma_s, sigma_a;
};
const Medium kGreyFog{{kFogSigmaS, kFogSigmaS, kFogSigmaS}, {kFogSigmaA, kFogSigmaA, kFogSigmaA}};
const Medium kColouredFog{kHgSigmaS, kHgSigmaA};

Vec3 vec(const scatterlut::Rgb &c) { return {c[0], c[1], c[2]}; }
Vec3 grey(double x) { return {x, x, x}; }
Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }

// Linear RGB radiance image, W/(m²·sr). airlight(q) gives the per-channel airlight of the
// geometry and intensity in q (its σ fields are the medium's channel 0: the grey fog's).
template <class AirFn, class NearFn>
std::vector<double> render(const Medium &fog, AirFn airlight, NearFn near_light) {
    std::vector<double> img(size_t{kWidth} * kHeight * 3);
    const Vec3 fwd = normalize(kTarget - kEye);
    const Vec3 right = normalize(cross(fwd, {0, 1, 0}));
    const Vec3 up = cross(right, fwd);
    const double th = std::tan(kFovY / 2), aspect = double(kWidth) / kHeight;
    const double eye[3] = {kEye.x, kEye.y, kEye.z};
    const Vec3 fog_t = vec(fog.sigma_s) + vec(fog.sigma_a);
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
            double px = (2 * (i + 0.5) / kWidth - 1) * th * aspect;
            double py = (1 - 2 * (j + 0.5) / kHeight) * th;
            Vec3 d = normalize(fwd + px * right + py * up);
            Hit h = trace(kEye, d);
            const double dir[3] = {d.x, d.y, d.z};
            Vec3 L{0, 0, 0};
            for (const Light &l : kLights) {
                const double lp[3] = {l.pos.x, l.pos.y, l.pos.z};
                auto q = scatterlut::airlight_query_from_points(eye, dir, lp, h.s, fog.sigma_s[0], fog.sigma_a[0], l.I0);
                L = L + airlight(q) * l.color;
            }
            if (h.slab) {
                Vec3 p = kEye + h.s * d;
                for (const Light &l : kLights) {
                    scatterlut::NearLightQuery q;
                    q.sigma_s_per_m = kSlabSigmaS;
                    q.sigma_a_per_m = kSlabSigmaA;
                    q.intensity_W_per_sr = l.I0;
                    q.normal[0] = 0, q.normal[1] = 0, q.normal[2] = 1;
                    q.eye_dir[0] = -d.x, q.eye_dir[1] = -d.y, q.eye_dir[2] = -d.z;
                    Vec3 rel = l.pos - p;
                    q.light_rel_m[0] = rel.x, q.light_rel_m[1] = rel.y, q.light_rel_m[2] = rel.z;
                    q.length_m = kInf;
                    // Fog attenuates the light on its way to the slab and the slab's glow on
                    // its way to the camera (the same factor in both renders).
                    const double path_m = std::sqrt(dot(rel, rel)) + h.s;
                    const Vec3 att{std::exp(-fog_t.x * path_m), std::exp(-fog_t.y * path_m),
                                   std::exp(-fog_t.z * path_m)};
                    const double Ln = near_light(q);
                    L = L + (grey(Ln) * att) * Vec3{l.color.x * kSlabColor.x, l.color.y * kSlabColor.y,
                                                    l.color.z * kSlabColor.z};
                }
            }
            double *o = &img[(size_t(j) * kWidth + i) * 3];
            o[0] = L.x, o[1] = L.y, o[2] = L.z;
        }
    return img;
}

// Reinhard on each channel after exposure, then the sRGB transfer curve, 8 bits.
std::vector<uint8_t> tone_map(const std::vector<double> &lin, double exposure) {
    std::vector<uint8_t> out(lin.size());
    for (size_t k = 0; k < lin.size(); ++k) {
        double x = lin[k] * exposure;
        double c = std::isinf(x) ? 1.0 : x / (1 + x);
        c = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
        out[k] = uint8_t(std::lround(std::clamp(c, 0.0, 1.0) * 255));
    }
    return out;
}

double psnr(double mse, double peak) { return mse > 0 ? 10 * std::log10(peak * peak / mse) : kInf; }

// Renders one picture pair (table, exact) of the street in `fog`, writes <stem>table.png and
// <stem>exact.png (the exposure from the exact image), prints times and PSNRs; false if the
// 8-bit PSNR is below 45 dB.
template <class TableAir, class ExactAir, class TableNear, class ExactNear>
bool render_pair(const std::string &dir, const std::string &stem, const char *title, const Medium &fog,
                 TableAir table_air, ExactAir exact_air, TableNear table_near, ExactNear exact_near) {
    using clk = std::chrono::steady_clock;
    auto t0 = clk::now();
    auto table_img = render(fog, table_air, table_near);
    auto t1 = clk::now();
    auto exact_img = render(fog, exact_air, exact_near);
    auto t2 = clk::now();
    const double ms_table = std::chrono::duration<double, std::milli>(t1 - t0).count();
    const double ms_exact = std::chrono::duration<double, std::milli>(t2 - t1).count();

    // Exposure from the exact image (median of the finite values → 0.025 after exposure: a night scene
    // whose lamps and lit slab stand out of the haze),
    // applied to both images.
    std::vector<double> v;
    double peak = 0;
    for (double x : exact_img)
        if (std::isfinite(x)) v.push_back(x), peak = std::max(peak, x);
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    const double exposure = 0.025 / std::max(v[v.size() / 2], 1e-30);

    auto t8 = tone_map(table_img, exposure), e8 = tone_map(exact_img, exposure);
    // Atomic writes; a failure (std::system_error naming the path) ends in main's catch.
    const std::string table_png = dir + "/" + stem + "table.png", exact_png = dir + "/" + stem + "exact.png";
    scatterlut::write_file_atomic(table_png, scatterlut::png::encode_rgb8(t8, kWidth, kHeight));
    scatterlut::write_file_atomic(exact_png, scatterlut::png::encode_rgb8(e8, kWidth, kHeight));

    double mse8 = 0, mse_lin = 0, max_rel = 0;
    size_t n_lin = 0, max8 = 0;
    for (size_t k = 0; k < e8.size(); ++k) {
        double d = double(t8[k]) - double(e8[k]);
        mse8 += d * d;
        max8 = std::max<size_t>(max8, size_t(std::fabs(d)));
        if (std::isfinite(exact_img[k]) && std::isfinite(table_img[k])) {
            double dl = table_img[k] - exact_img[k];
            mse_lin += dl * dl;
            ++n_lin;
            if (exact_img[k] > 0) max_rel = std::max(max_rel, std::fabs(dl) / exact_img[k]);
        }
    }
    mse8 /= double(e8.size());
    mse_lin /= double(std::max<size_t>(n_lin, 1));
    const double p8 = psnr(mse8, 255), plin = psnr(mse_lin, peak);

    std::printf("%s\n", title);
    std::printf("image %dx%d, %zu lights, %zu pixel values\n", kWidth, kHeight, kLights.size(), e8.size());
    std::printf("time table: %.1f ms  (%.2f us/pixel)\n", ms_table, 1e3 * ms_table / (kWidth * kHeight));
    std::printf("time exact: %.1f ms  (%.2f us/pixel)\n", ms_exact, 1e3 * ms_exact / (kWidth * kHeight));
    std::printf("PSNR 8-bit tone-mapped: %.2f dB (max |diff| %zu levels)\n", p8, max8);
    std::printf("exposure %.17g (the web demo's exposure= for the same picture)\n", exposure);
    std::printf("PSNR linear radiance (peak %.4g W/(m2 sr)): %.2f dB; max rel error %.3g\n", peak, plin, max_rel);
    std::printf("wrote %s and %s\n", table_png.c_str(), exact_png.c_str());
    if (!(p8 >= 45.0)) {
        std::printf("FAIL: 8-bit PSNR %.2f dB < 45 dB (%s)\n", p8, title);
        return false;
    }
    return true;
}

} // namespace

int main(int argc, char **argv) {
    if (argc != 4 && argc != 5) {
        std::fprintf(stderr, "usage: %s airlight_F.slut near_light_E3.slut out_dir [airlight_Fg_g0.85.slut]\n",
                     argv[0]);
        return 2;
    }
    try {
        const scatterlut::AirlightTable fog(scatterlut::load_table(argv[1]));
        const scatterlut::NearLightTable wax(scatterlut::load_table(argv[2]));
        const std::string dir = argv[3];
        // The anisotropic table is read (and checked) before anything is rendered or written.
        std::unique_ptr<scatterlut::AirlightHgTable> fog_hg;
        if (argc == 5) {
            fog_hg = std::make_unique<scatterlut::AirlightHgTable>(scatterlut::load_table(argv[4]));
            if (fog_hg->phase_g() != kHgPhaseG) {
                std::fprintf(stderr, "render_fog: %s: the table's phase.g is %.17g, the coloured fog's is %.17g\n",
                             argv[4], fog_hg->phase_g(), kHgPhaseG);
                return 2;
            }
        }
        const auto table_near = [&](const scatterlut::NearLightQuery &q) { return wax.radiance(q); };
        const auto exact_near = [](const scatterlut::NearLightQuery &q) {
            return scatterlut::near_light_radiance_exact(q);
        };

        bool ok = render_pair(
            dir, "", "isotropic grey fog (airlight_F)", kGreyFog,
            [&](const scatterlut::AirlightQuery &q) { return grey(fog.radiance(q)); },
            [](const scatterlut::AirlightQuery &q) { return grey(scatterlut::airlight_radiance_exact(q)); },
            table_near, exact_near);

        if (fog_hg) {
            std::printf("\n");
            const bool ok_hg = render_pair(
                dir, "hg_", "forward-scattering coloured fog (airlight_Fg, g = 0.85, per-channel sigma)", kColouredFog,
                [&](const scatterlut::AirlightQuery &q) {
                    return vec(fog_hg->radiance_rgb(q, kColouredFog.sigma_s, kColouredFog.sigma_a));
                },
                [](const scatterlut::AirlightQuery &q) {
                    return vec(scatterlut::airlight_radiance_exact_rgb(q, kColouredFog.sigma_s, kColouredFog.sigma_a,
                                                                      kHgPhaseG));
                },
                table_near, exact_near);
            ok = ok && ok_hg;
        }
        return ok ? 0 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "render_fog: %s\n", e.what());
        return 2;
    }
}
