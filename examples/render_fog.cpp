// render_fog — a foggy street with glowing lamps and a lit translucent slab, rendered
// twice: from the scatterlut tables (AirlightTable, NearLightTable) and from the exact
// quadratures (airlight_radiance_exact, near_light_radiance_exact). Writes table.png and
// exact.png (identical tone mapping) and prints the PSNR between them and the time each
// image took. Exits 1 if the 8-bit PSNR is below 45 dB.
//
//   render_fog out/airlight_F.slut out/near_light_E3.slut out_dir
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
#include <string>
#include <vector>

#include "scatterlut/airlight.hpp"
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

// Linear RGB radiance image, W/(m²·sr).
template <class AirFn, class NearFn>
std::vector<double> render(AirFn airlight, NearFn near_light) {
    std::vector<double> img(size_t{kWidth} * kHeight * 3);
    const Vec3 fwd = normalize(kTarget - kEye);
    const Vec3 right = normalize(cross(fwd, {0, 1, 0}));
    const Vec3 up = cross(right, fwd);
    const double th = std::tan(kFovY / 2), aspect = double(kWidth) / kHeight;
    const double eye[3] = {kEye.x, kEye.y, kEye.z};
    const double fog_t = kFogSigmaS + kFogSigmaA;
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
                auto q = scatterlut::airlight_query_from_points(eye, dir, lp, h.s, kFogSigmaS, kFogSigmaA, l.I0);
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
                    double att = std::exp(-fog_t * (std::sqrt(dot(rel, rel)) + h.s));
                    double Ln = near_light(q) * att;
                    L = L + Ln * Vec3{l.color.x * kSlabColor.x, l.color.y * kSlabColor.y,
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

} // namespace

int main(int argc, char **argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s airlight_F.slut near_light_E3.slut out_dir\n", argv[0]);
        return 2;
    }
    try {
        const scatterlut::AirlightTable fog(scatterlut::load_table(argv[1]));
        const scatterlut::NearLightTable wax(scatterlut::load_table(argv[2]));
        const std::string dir = argv[3];
        using clk = std::chrono::steady_clock;

        auto t0 = clk::now();
        auto table_img = render([&](const scatterlut::AirlightQuery &q) { return fog.radiance(q); },
                                [&](const scatterlut::NearLightQuery &q) { return wax.radiance(q); });
        auto t1 = clk::now();
        auto exact_img = render([](const scatterlut::AirlightQuery &q) { return scatterlut::airlight_radiance_exact(q); },
                                [](const scatterlut::NearLightQuery &q) { return scatterlut::near_light_radiance_exact(q); });
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
        // Atomic writes; a failure (std::system_error naming the path) ends in the catch below.
        scatterlut::write_file_atomic(dir + "/table.png", scatterlut::png::encode_rgb8(t8, kWidth, kHeight));
        scatterlut::write_file_atomic(dir + "/exact.png", scatterlut::png::encode_rgb8(e8, kWidth, kHeight));

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

        std::printf("image %dx%d, %zu lights, %zu pixel values\n", kWidth, kHeight, kLights.size(), e8.size());
        std::printf("time table: %.1f ms  (%.2f us/pixel)\n", ms_table, 1e3 * ms_table / (kWidth * kHeight));
        std::printf("time exact: %.1f ms  (%.2f us/pixel)\n", ms_exact, 1e3 * ms_exact / (kWidth * kHeight));
        std::printf("PSNR 8-bit tone-mapped: %.2f dB (max |diff| %zu levels)\n", p8, max8);
        std::printf("exposure %.17g (the web demo's exposure= for the same picture)\n", exposure);
        std::printf("PSNR linear radiance (peak %.4g W/(m2 sr)): %.2f dB; max rel error %.3g\n", peak, plin, max_rel);
        std::printf("wrote %s/table.png and %s/exact.png\n", dir.c_str(), dir.c_str());
        if (!(p8 >= 45.0)) {
            std::printf("FAIL: 8-bit PSNR %.2f dB < 45 dB\n", p8);
            return 1;
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "render_fog: %s\n", e.what());
        return 2;
    }
}
