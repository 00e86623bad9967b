// render_fog — a foggy street with glowing lamps and a lit translucent slab, rendered
// twice: from the scatterlut tables (AirlightTable, NearLightTable) and from the exact
// quadratures (airlight_radiance_exact, near_light_radiance_exact). Writes table.png and
// exact.png (identical tone mapping) and prints the PSNR between them and the time each
// image took. Exits 1 if an 8-bit PSNR is below 45 dB.
//
// The same street with its lamps as spot lights under shades and a parked car's headlights
// (glTF KHR_lights_punctual cones, docs/SPOT.md): the table path (spot_airlight_radiance)
// against the exact spot airlight (spot_airlight_radiance_exact), spots_table.png and
// spots_exact.png. A spot lights the slab and the street's surfaces as a point light masked by
// its falloff towards the point (spot_falloff; the same in both renders).
//
// Given an anisotropic airlight table of g = 0.85 (kind airlight_Fg, from
// `scatterlut generate --scene examples/scenes/fog_forward.toml`), it renders the spot-lit
// street in forward-scattering, coloured fog (Henyey–Greenstein phase, per-channel
// coefficients): the spots' glow from that one table per channel
// (spot_airlight_radiance_rgb) and exactly (spot_airlight_radiance_exact_rgb), written to
// hg_table.png and hg_exact.png, with the same PSNR check.
//
// With --street it renders the spot-lit grey-fog street with side walls and its ground,
// walls and far wall lit by every lamp through the fog (scatterlut/surface_radiance.hpp: the
// direct light plus Sun et al. 2005's scattered terms E_ss and S_n; the wet road has a Phong
// lobe), from G tables it fills itself by quadrature and with G by quadrature per pixel:
// street_table.png and street_exact.png (small: the exact G costs ~1 ms per pixel and lamp),
// the same PSNR check, and street_full_table.png (480 × 270, tables only).
//
//   render_fog out/airlight_F.slut out/near_light_E3.slut out_dir [out_fwd/airlight_Fg_g0.85.slut] [--street]
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
#include <thread>
#include <vector>

#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/anisotropic.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/spot.hpp"
#include "scatterlut/surface_radiance.hpp"
#include "scatterlut/surface_table.hpp"
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

// A point light, or a spot with glTF KHR_lights_punctual's cone (docs/SPOT.md): I0 on its
// axis, the falloff between the inner and outer half-angles; 180° and 180°: a point light.
struct Light {
    Vec3 pos;       // m
    double I0;      // W/sr (a spot's on its axis)
    Vec3 color;     // relative spectral tint (grey medium: radiance × color)
    Vec3 axis{0, -1, 0};                       // a spot's axis, light → lit points (need not be unit)
    double outer_deg = 180.0, inner_deg = 180.0; // its cone's half-angles θ_o ≥ θ_i
};

scatterlut::SpotLight spot_of(const Light &l) {
    scatterlut::SpotLight s;
    s.position_m = {l.pos.x, l.pos.y, l.pos.z};
    s.direction = {l.axis.x, l.axis.y, l.axis.z};
    s.outer_angle_rad = l.outer_deg * 3.14159265358979323846 / 180.0;
    s.inner_angle_rad = l.inner_deg * 3.14159265358979323846 / 180.0;
    s.intensity_W_per_sr = l.I0;
    return s;
}

// glTF's falloff of the light towards p (1 for a point light).
double falloff_towards(const Light &l, Vec3 p) { return scatterlut::spot_falloff(spot_of(l), {p.x, p.y, p.z}); }

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

// The street's lamps as point lights: the first picture (README's).
const std::vector<Light> kPointLights = {
    {{-3.5, 5.0, -12.0}, 300.0, {1.0, 0.72, 0.38}},  // sodium lamps along the street
    {{3.8, 5.0, -26.0}, 300.0, {1.0, 0.72, 0.38}},
    {{-3.8, 5.0, -45.0}, 300.0, {1.0, 0.72, 0.38}},
    {{3.8, 5.0, -70.0}, 300.0, {1.0, 0.72, 0.38}},
    {{2.0, 1.2, -8.6}, 40.0, {0.85, 0.9, 1.0}},       // small lamp 0.4 m in front of the slab
    {{-2.0, 4.0, 3.0}, 200.0, {1.0, 0.72, 0.38}},    // behind the camera, out of view
};

// The same street with its lamps as spots under shades shining down and a little towards the
// street's middle (glTF falloff from 35° to 55° off the axis), and a car parked across the
// street at z = −20 m shining its headlights towards the left pavement (12° to 20°, tilted
// 3.4° down): beams seen from beside. The bare bulb before the slab stays a point light. The
// other pictures (spots_, hg_, street_); the web demo (examples/web/fog.mjs) draws spots_ and its
// test (WebDemoChromium) compares its frame with spots_table.png.
const std::vector<Light> kSpotLights = {
    {{-3.5, 5.0, -12.0}, 300.0, {1.0, 0.72, 0.38}, {0.35, -1.0, 0.0}, 55.0, 35.0}, // sodium lamps
    {{3.8, 5.0, -26.0}, 300.0, {1.0, 0.72, 0.38}, {-0.35, -1.0, 0.0}, 55.0, 35.0},
    {{-3.8, 5.0, -45.0}, 300.0, {1.0, 0.72, 0.38}, {0.35, -1.0, 0.0}, 55.0, 35.0},
    {{3.8, 5.0, -70.0}, 300.0, {1.0, 0.72, 0.38}, {-0.35, -1.0, 0.0}, 55.0, 35.0},
    {{2.0, 1.2, -8.6}, 40.0, {0.85, 0.9, 1.0}},                                      // bare bulb before the slab
    {{-2.0, 4.0, 3.0}, 200.0, {1.0, 0.72, 0.38}, {0.35, -1.0, 0.0}, 55.0, 35.0},     // behind the camera
    {{2.2, 0.75, -19.3}, 800.0, {0.9, 0.95, 1.0}, {-1.0, -0.06, 0.0}, 20.0, 12.0},  // the car's headlights
    {{2.2, 0.75, -20.7}, 800.0, {0.9, 0.95, 1.0}, {-1.0, -0.06, 0.0}, 20.0, 12.0},
};

// The lit street's surfaces (the street pair only; the first pictures keep the ground and
// far wall unlit, and no side walls).
enum class Surface { none, ground, left_wall, right_wall, far_wall };

struct Hit {
    double s = kInf;   // ray length in the fog
    bool slab = false; // hit the slab face
    Surface surface = Surface::none;
    Vec3 normal{0, 0, 0}; // the surface's unit normal, facing the street
};

// The street's side walls (street pair only): planes x = ±kStreetHalfWidth, y ∈ [0, kSideWallH],
// z ∈ [kWallZ, kSideWallZ0], facing the street.
constexpr double kStreetHalfWidth = 7.0, kSideWallH = 11.0, kSideWallZ0 = 12.0;

Hit trace(Vec3 o, Vec3 d, bool street) {
    Hit h;
    if (d.y < 0) { // ground y = 0
        double t = -o.y / d.y;
        if (t < h.s) h.s = t, h.surface = Surface::ground, h.normal = {0, 1, 0};
    }
    if (d.z < 0) {
        double t = (kWallZ - o.z) / d.z;
        Vec3 p = o + t * d;
        if (t < h.s && p.y <= kWallH) h.s = t, h.surface = Surface::far_wall, h.normal = {0, 0, 1};
        t = (kSlabZ - o.z) / d.z;
        p = o + t * d;
        if (t < h.s && p.x >= kSlabX0 && p.x <= kSlabX1 && p.y >= 0 && p.y <= kSlabH) {
            h.s = t;
            h.slab = true;
            h.surface = Surface::none;
        }
    }
    if (street && d.x != 0) {
        const double wall_x = d.x < 0 ? -kStreetHalfWidth : kStreetHalfWidth;
        const double t = (wall_x - o.x) / d.x;
        const Vec3 p = o + t * d;
        if (t > 0 && t < h.s && p.y >= 0 && p.y <= kSideWallH && p.z >= kWallZ && p.z <= kSideWallZ0) {
            h.s = t;
            h.slab = false;
            h.surface = d.x < 0 ? Surface::left_wall : Surface::right_wall;
            h.normal = {d.x < 0 ? 1.0 : -1.0, 0, 0};
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

// One picture: its size and whether the street's surfaces are lit (the street pair: side
// walls, and the ground, walls and far wall lit through the fog by every lamp).
struct Picture {
    const std::vector<Light> *lights = &kPointLights;
    int width = kWidth, height = kHeight;
    bool street = false;
    double key = 0.025; // the exact image's median radiance after exposure (tone mapping)
};

// The street's materials (street pair): Sun et al. 2005's Lambertian term plus, on the wet
// road, an unnormalised Phong lobe of exponent kWetExponent (scatterlut/surface_radiance.hpp).
constexpr int kWetExponent = 20;
struct StreetMaterial {
    scatterlut::SurfaceMaterial reflectance;
    Vec3 colour; // relative tint of the albedo
};
StreetMaterial street_material(Surface s) {
    StreetMaterial m;
    if (s == Surface::ground) {
        // Wet asphalt: dark diffuse, a specular lobe of albedo 0.3 (energy-conserving k_s).
        m.reflectance.diffuse_albedo = 0.1;
        m.reflectance.phong_exponent = kWetExponent;
        m.reflectance.specular_per_sr = 0.3 * (kWetExponent + 2) / (2.0 * 3.14159265358979323846);
        m.colour = {0.85, 0.85, 0.9};
    } else if (s == Surface::far_wall) {
        m.reflectance.diffuse_albedo = 0.35;
        m.colour = {0.8, 0.8, 0.85};
    } else { // side walls: light plaster
        m.reflectance.diffuse_albedo = 0.5;
        m.colour = {0.95, 0.85, 0.72};
    }
    return m;
}

// Linear RGB radiance image, W/(m²·sr). airlight(q) gives the per-channel airlight of the
// geometry and intensity in q (its σ fields are the medium's channel 0: the grey fog's);
// surface(lighting, material) the radiance a street surface sends to the camera from one
// lamp through the grey fog (picture.street only). Rows are shared among the CPU's threads
// (each pixel is computed alone: the image does not depend on the thread count).
template <class AirFn, class NearFn, class SurfFn>
std::vector<double> render(const Picture &picture, const Medium &fog, AirFn airlight, NearFn near_light,
                           SurfFn surface) {
    const int width = picture.width, height = picture.height;
    std::vector<double> img(size_t(width) * height * 3);
    const Vec3 fwd = normalize(kTarget - kEye);
    const Vec3 right = normalize(cross(fwd, {0, 1, 0}));
    const Vec3 up = cross(right, fwd);
    const double th = std::tan(kFovY / 2), aspect = double(width) / height;
    const double eye[3] = {kEye.x, kEye.y, kEye.z};
    const Vec3 fog_t = vec(fog.sigma_s) + vec(fog.sigma_a);
    const auto pixel = [&](int i, int j) {
        double px = (2 * (i + 0.5) / width - 1) * th * aspect;
        double py = (1 - 2 * (j + 0.5) / height) * th;
        Vec3 d = normalize(fwd + px * right + py * up);
        Hit h = trace(kEye, d, picture.street);
        const double dir[3] = {d.x, d.y, d.z};
        Vec3 L{0, 0, 0};
        for (const Light &l : *picture.lights) {
            scatterlut::SpotQuery q;
            q.sigma_s_per_m = fog.sigma_s[0];
            q.sigma_a_per_m = fog.sigma_a[0];
            q.viewer_m = {eye[0], eye[1], eye[2]};
            q.view_dir = {dir[0], dir[1], dir[2]};
            q.length_m = h.s;
            q.light = spot_of(l);
            L = L + airlight(q) * l.color;
        }
        if (h.slab) {
            Vec3 p = kEye + h.s * d;
            for (const Light &l : *picture.lights) {
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
                // A spot lights the slab as a point light masked by its falloff towards the
                // point (the near light has no cone; the same factor in both renders).
                const double Ln = near_light(q) * falloff_towards(l, p);
                L = L + (grey(Ln) * att) * Vec3{l.color.x * kSlabColor.x, l.color.y * kSlabColor.y,
                                                l.color.z * kSlabColor.z};
            }
        }
        if (picture.street && h.surface != Surface::none && std::isfinite(h.s)) {
            // The street's surfaces: the radiance of each lamp's light reaching the point
            // directly and scattered by the fog (Sun et al. 2005), seen through the fog.
            // The view ray's own airlight is the sum above.
            const Vec3 p = kEye + h.s * d;
            const StreetMaterial m = street_material(h.surface);
            scatterlut::SurfaceLighting s;
            s.point_m[0] = p.x, s.point_m[1] = p.y, s.point_m[2] = p.z;
            s.normal[0] = h.normal.x, s.normal[1] = h.normal.y, s.normal[2] = h.normal.z;
            s.viewer_m[0] = kEye.x, s.viewer_m[1] = kEye.y, s.viewer_m[2] = kEye.z;
            for (const Light &l : *picture.lights) {
                s.light_m[0] = l.pos.x, s.light_m[1] = l.pos.y, s.light_m[2] = l.pos.z;
                // A spot: the point light's terms times its falloff towards the point (exact
                // for the direct terms; for the scattered ones the approximation of
                // docs/SPOT.md, "Surfaces lit by a spot"; the same in both renders).
                s.intensity_W_per_sr = l.I0 * falloff_towards(l, p);
                L = L + grey(surface(s, m.reflectance)) * (l.color * m.colour);
            }
        }
        double *o = &img[(size_t(j) * width + i) * 3];
        o[0] = L.x, o[1] = L.y, o[2] = L.z;
    };
    const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
    std::vector<std::exception_ptr> failed(static_cast<size_t>(threads));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            try {
                for (int j = t; j < height; j += threads)
                    for (int i = 0; i < width; ++i) pixel(i, j);
            } catch (...) {
                failed[size_t(t)] = std::current_exception();
            }
        });
    for (std::thread &t : pool) t.join();
    for (const std::exception_ptr &e : failed)
        if (e) std::rethrow_exception(e);
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
template <class TableAir, class ExactAir, class TableNear, class ExactNear, class TableSurf, class ExactSurf>
bool render_pair(const std::string &dir, const std::string &stem, const char *title, const Picture &picture,
                 const Medium &fog, TableAir table_air, ExactAir exact_air, TableNear table_near, ExactNear exact_near,
                 TableSurf table_surface, ExactSurf exact_surface, double *exposure_out = nullptr) {
    using clk = std::chrono::steady_clock;
    const int width = picture.width, height = picture.height;
    auto t0 = clk::now();
    auto table_img = render(picture, fog, table_air, table_near, table_surface);
    auto t1 = clk::now();
    auto exact_img = render(picture, fog, exact_air, exact_near, exact_surface);
    auto t2 = clk::now();
    const double ms_table = std::chrono::duration<double, std::milli>(t1 - t0).count();
    const double ms_exact = std::chrono::duration<double, std::milli>(t2 - t1).count();

    // Exposure from the exact image (median of the finite values → picture.key after exposure,
    // 0.025: a night scene whose lamps and lit slab stand out of the haze), applied to both images.
    std::vector<double> v;
    double peak = 0;
    for (double x : exact_img)
        if (std::isfinite(x)) v.push_back(x), peak = std::max(peak, x);
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    const double exposure = picture.key / std::max(v[v.size() / 2], 1e-30);
    if (exposure_out) *exposure_out = exposure;

    auto t8 = tone_map(table_img, exposure), e8 = tone_map(exact_img, exposure);
    // Atomic writes; a failure (std::system_error naming the path) ends in main's catch.
    const std::string table_png = dir + "/" + stem + "table.png", exact_png = dir + "/" + stem + "exact.png";
    scatterlut::write_file_atomic(table_png, scatterlut::png::encode_rgb8(t8, width, height));
    scatterlut::write_file_atomic(exact_png, scatterlut::png::encode_rgb8(e8, width, height));

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
    std::printf("image %dx%d, %zu lights, %zu pixel values, %u threads\n", width, height, picture.lights->size(), e8.size(),
                std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
    std::printf("time table: %.1f ms  (%.2f us/pixel)\n", ms_table, 1e3 * ms_table / (width * height));
    std::printf("time exact: %.1f ms  (%.2f us/pixel)\n", ms_exact, 1e3 * ms_exact / (width * height));
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

// The lit street (--street): the grey-fog street with side walls, its ground, walls and far
// wall lit by every lamp through the fog (scatterlut/surface_radiance.hpp: the direct terms
// and Sun et al. 2005's scattered terms E_ss and S_n; wet road: a Phong lobe), from G tables
// and with G by quadrature per pixel and lamp (surface_G_exact, ~1e-10 relative, ~1 ms per
// call: the expensive part, so the tested pair is small, kStreetWidth × kStreetHeight). The
// same street from the tables alone at the full 480 × 270 is written beside it
// (street_full_table.png, the exposure of the pair). The G tables are filled here on the CPU
// by quadrature (surface_G*_table_by_quadrature) on T ∈ [0, T_max], T_max = σ_t times the
// farthest lamp–street distance (at a corner of the street's box, where it is largest).
constexpr int kStreetWidth = 64, kStreetHeight = 36;
constexpr int kStreetTableT = 24, kStreetTableTheta = 25; // nodes of the G tables (T × θ)
constexpr double kStreetKey = 0.08; // a brighter key than the first pictures: the lit surfaces

template <class TableAir, class ExactAir, class TableNear, class ExactNear>
bool render_street(const std::string &dir, TableAir table_air, ExactAir exact_air, TableNear table_near,
                   ExactNear exact_near) {
    using clk = std::chrono::steady_clock;
    double far_m = 0;
    for (const Light &l : kSpotLights)
        for (double x : {-kStreetHalfWidth, kStreetHalfWidth})
            for (double y : {0.0, kWallH})
                for (double z : {kWallZ, kSideWallZ0}) {
                    const Vec3 r = Vec3{x, y, z} - l.pos;
                    far_m = std::max(far_m, std::sqrt(dot(r, r)));
                }
    const double T_max = (kFogSigmaS + kFogSigmaA) * far_m;
    const auto t0 = clk::now();
    const scatterlut::SurfaceTable g0(scatterlut::surface_G_table_by_quadrature(1, T_max, kStreetTableT, kStreetTableTheta));
    const scatterlut::SurfaceTable gn(
        scatterlut::surface_G_table_by_quadrature(kWetExponent, T_max, kStreetTableT, kStreetTableTheta));
    const double ms_tables = std::chrono::duration<double, std::milli>(clk::now() - t0).count();
    std::printf("lit street: G0 and G%d tables %dx%d on T <= %.3f filled by quadrature in %.1f ms\n", kWetExponent,
                kStreetTableT, kStreetTableTheta, T_max, ms_tables);
    scatterlut::SurfaceTables tables;
    tables.diffuse = &g0;
    tables.specular = &gn;
    const auto table_surface = [&](const scatterlut::SurfaceLighting &s, const scatterlut::SurfaceMaterial &m) {
        return scatterlut::surface_radiance(tables, s, kFogSigmaS, kFogSigmaA, m).total();
    };
    const auto exact_surface = [](const scatterlut::SurfaceLighting &s, const scatterlut::SurfaceMaterial &m) {
        return scatterlut::surface_radiance_exact(s, kFogSigmaS, kFogSigmaA, m).total();
    };
    Picture picture;
    picture.lights = &kSpotLights;
    picture.width = kStreetWidth;
    picture.height = kStreetHeight;
    picture.street = true;
    picture.key = kStreetKey;
    double exposure = 0;
    const bool ok = render_pair(dir, "street_", "lit street: ground and walls lit through the grey fog (surface_G)",
                                picture, kGreyFog, table_air, exact_air, table_near, exact_near, table_surface,
                                exact_surface, &exposure);
    Picture full = picture;
    full.width = kWidth;
    full.height = kHeight;
    const auto t1 = clk::now();
    const std::vector<double> img = render(full, kGreyFog, table_air, table_near, table_surface);
    const double ms_full = std::chrono::duration<double, std::milli>(clk::now() - t1).count();
    const std::string full_png = dir + "/street_full_table.png";
    scatterlut::write_file_atomic(full_png, scatterlut::png::encode_rgb8(tone_map(img, exposure), kWidth, kHeight));
    std::printf("lit street %dx%d from the tables: %.1f ms; wrote %s\n", kWidth, kHeight, ms_full, full_png.c_str());
    return ok;
}

} // namespace

int main(int argc, char **argv) {
    std::vector<std::string> args;
    bool street = false;
    for (int k = 1; k < argc; ++k) {
        if (std::string(argv[k]) == "--street") street = true;
        else args.emplace_back(argv[k]);
    }
    if (args.size() != 3 && args.size() != 4) {
        std::fprintf(stderr, "usage: %s airlight_F.slut near_light_E3.slut out_dir [airlight_Fg_g0.85.slut] [--street]\n",
                     argv[0]);
        return 2;
    }
    try {
        const scatterlut::AirlightTable fog(scatterlut::load_table(args[0]));
        const scatterlut::NearLightTable wax(scatterlut::load_table(args[1]));
        const std::string dir = args[2];
        // The anisotropic table is read (and checked) before anything is rendered or written.
        std::unique_ptr<scatterlut::AirlightHgTable> fog_hg;
        if (args.size() == 4) {
            fog_hg = std::make_unique<scatterlut::AirlightHgTable>(scatterlut::load_table(args[3]));
            if (fog_hg->phase_g() != kHgPhaseG) {
                std::fprintf(stderr, "render_fog: %s: the table's phase.g is %.17g, the coloured fog's is %.17g\n",
                             args[3].c_str(), fog_hg->phase_g(), kHgPhaseG);
                return 2;
            }
        }
        const auto table_near = [&](const scatterlut::NearLightQuery &q) { return wax.radiance(q); };
        const auto exact_near = [](const scatterlut::NearLightQuery &q) {
            return scatterlut::near_light_radiance_exact(q);
        };
        // Every light through the spot calls (a point light's cone is the whole sphere: the
        // point-light table and quadrature, bit for bit).
        const auto table_air = [&](const scatterlut::SpotQuery &q) { return grey(scatterlut::spot_airlight_radiance(fog, q)); };
        const auto exact_air = [](const scatterlut::SpotQuery &q) {
            return grey(scatterlut::spot_airlight_radiance_exact(q));
        };
        const auto unlit = [](const scatterlut::SurfaceLighting &, const scatterlut::SurfaceMaterial &) { return 0.0; };

        bool ok = render_pair(dir, "", "isotropic grey fog (airlight_F)", Picture{}, kGreyFog, table_air, exact_air,
                              table_near, exact_near, unlit, unlit);
        // The street lamps as spots and a car's headlights (docs/SPOT.md): the table path
        // (spot_airlight_radiance) against the exact spot airlight.
        std::printf("\n");
        Picture spots;
        spots.lights = &kSpotLights;
        ok = render_pair(dir, "spots_", "spot lights in isotropic grey fog (airlight_F, spot_airlight_radiance)", spots,
                         kGreyFog, table_air, exact_air, table_near, exact_near, unlit, unlit) &&
             ok;

        if (fog_hg) {
            std::printf("\n");
            const bool ok_hg = render_pair(
                dir, "hg_", "spot lights in forward-scattering coloured fog (airlight_Fg, g = 0.85, per-channel sigma)", spots,
                kColouredFog,
                [&](const scatterlut::SpotQuery &q) {
                    return vec(scatterlut::spot_airlight_radiance_rgb(*fog_hg, q, kColouredFog.sigma_s,
                                                                      kColouredFog.sigma_a));
                },
                [](const scatterlut::SpotQuery &q) {
                    return vec(scatterlut::spot_airlight_radiance_exact_rgb(q, kColouredFog.sigma_s,
                                                                           kColouredFog.sigma_a, kHgPhaseG));
                },
                table_near, exact_near, unlit, unlit);
            ok = ok && ok_hg;
        }

        if (street) {
            std::printf("\n");
            ok = render_street(dir, table_air, exact_air, table_near, exact_near) && ok;
        }
        return ok ? 0 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "render_fog: %s\n", e.what());
        return 2;
    }
}
