// Tests of table pictures (`scatterlut inspect --preview`) and the PNG encoder.
//
// References: the PNG specification and zlib itself — files are decoded here with zlib's
// uncompress() and checked with zlib's crc32(), independent of the encoder under test;
// the published CRC-32 / Adler-32 check values; viridis' entries from matplotlib's
// table (_viridis_data, CC0); synthetic tables whose values are linear in one axis's unit
// coordinate, so multilinear interpolation is exact and the colour of every plot pixel is
// known in advance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include "cli_runner.hpp"
#include "png_writer.hpp"
#include "preview.hpp"
#include "scatterlut/io.hpp"

using namespace scatterlut;
using Bytes = std::vector<uint8_t>;

namespace scatterlut { // found by argument-dependent lookup from gtest's comparisons
bool operator==(Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }
std::ostream &operator<<(std::ostream &o, Rgb c) {
    return o << "(" << int(c.r) << ", " << int(c.g) << ", " << int(c.b) << ")";
}
} // namespace scatterlut

namespace {

// --- a PNG decoder on zlib, for 8-bit RGB files with filter type 0 --------------------
struct DecodedPng {
    int width = 0, height = 0;
    Bytes rgb;
};

uint32_t be32(const uint8_t *p) { return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3]; }

// Throws std::runtime_error saying what is wrong.
DecodedPng decode_png(const Bytes &b) {
    const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (b.size() < 8 || std::memcmp(b.data(), signature, 8) != 0) throw std::runtime_error("bad signature");
    DecodedPng png;
    Bytes idat;
    bool ended = false;
    size_t pos = 8, chunks = 0;
    while (pos < b.size()) {
        if (b.size() - pos < 12) throw std::runtime_error("truncated chunk");
        const uint32_t len = be32(&b[pos]);
        if (b.size() - pos - 12 < len) throw std::runtime_error("chunk runs past the file");
        const std::string type(reinterpret_cast<const char *>(&b[pos + 4]), 4);
        const uint8_t *data = &b[pos + 8];
        const uint32_t crc = be32(&b[pos + 8 + len]);
        if (crc != static_cast<uint32_t>(::crc32(0, &b[pos + 4], len + 4)))
            throw std::runtime_error("CRC mismatch in chunk " + type);
        if (chunks++ == 0 && type != "IHDR") throw std::runtime_error("first chunk is not IHDR");
        if (type == "IHDR") {
            if (len != 13) throw std::runtime_error("IHDR length");
            png.width = static_cast<int>(be32(data));
            png.height = static_cast<int>(be32(data + 4));
            if (data[8] != 8 || data[9] != 2 || data[10] != 0 || data[11] != 0 || data[12] != 0)
                throw std::runtime_error("not 8-bit RGB, deflate, filter 0, no interlace");
        } else if (type == "IDAT") {
            idat.insert(idat.end(), data, data + len);
        } else if (type == "IEND") {
            ended = true;
        }
        pos += 12 + len;
    }
    if (!ended) throw std::runtime_error("no IEND");
    const size_t row = 1 + 3 * static_cast<size_t>(png.width);
    Bytes raw(row * static_cast<size_t>(png.height) + 1); // one spare byte: a longer stream shows up
    uLongf raw_len = raw.size();
    if (::uncompress(raw.data(), &raw_len, idat.data(), idat.size()) != Z_OK)
        throw std::runtime_error("zlib cannot uncompress the IDAT stream");
    if (raw_len != row * static_cast<size_t>(png.height))
        throw std::runtime_error("IDAT holds " + std::to_string(raw_len) + " bytes, expected " +
                                 std::to_string(row * static_cast<size_t>(png.height)));
    for (int j = 0; j < png.height; ++j) {
        if (raw[static_cast<size_t>(j) * row] != 0) throw std::runtime_error("filter type is not 0");
        png.rgb.insert(png.rgb.end(), raw.begin() + static_cast<long>(j * row + 1),
                       raw.begin() + static_cast<long>((j + 1) * row));
    }
    return png;
}

Rgb pixel(const Bytes &rgb, int width, int x, int y) {
    const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

// How far relative luminance may fall between neighbouring colours of the 8-bit map:
// rounding moves a channel by up to one level (see Viridis test).
constexpr double kLuminanceSlack = 5e-4;

// Relative luminance (Rec. 709 primaries) of an sRGB colour.
double luminance(Rgb c) {
    auto lin = [](uint8_t v) {
        const double x = v / 255.0;
        return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
    };
    return 0.2126 * lin(c.r) + 0.7152 * lin(c.g) + 0.0722 * lin(c.b);
}

// --- synthetic tables -----------------------------------------------------------------

Axis axis(const char *name, double min, double max, int warp, int count) {
    Axis a;
    a.name = name;
    a.meaning = std::string("test axis ") + name;
    a.map = slut_axis{min, max, 0.0, warp, count};
    return a;
}

// Axes a (linear [0, 1], 5 nodes), b (log [1e-3, 1], 4 nodes), optionally c (linear
// [0, 10], 6 nodes); one linear channel v = f(unit coordinates of a, b, c).
template <class F> Table make_table(bool three_d, F value_of_units) {
    Table t;
    t.kind = "test_preview";
    t.quantity_version = 1;
    t.storage = Storage::F64;
    t.axes = {axis("a", 0.0, 1.0, SLUT_WARP_LINEAR, 5), axis("b", 1e-3, 1.0, SLUT_WARP_LOG, 4)};
    if (three_d) t.axes.push_back(axis("c", 0.0, 10.0, SLUT_WARP_LINEAR, 6));
    t.channels = {Channel{"v", "test value", Encoding::Linear}};
    const int nc = three_d ? 6 : 1;
    for (int k = 0; k < nc; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 5; ++i) t.values.push_back(value_of_units(i / 4.0, j / 3.0, nc > 1 ? k / 5.0 : 0.0));
    t.check_consistent();
    return t;
}

template <class F> void expect_invalid(F f, const std::string &needle) {
    try {
        f();
        ADD_FAILURE() << "no std::invalid_argument; expected one containing '" << needle << "'";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}

const PreviewTick *find_tick(const std::vector<PreviewTick> &ticks, const std::string &label) {
    for (const PreviewTick &k : ticks)
        if (k.label == label) return &k;
    return nullptr;
}

Bytes read_all(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace

// ====================================================================================
// PNG encoder
// ====================================================================================

// CRC-32 of "123456789" is 0xcbf43926 (the standard check value); Adler-32 of
// "Wikipedia" is 0x11e60398 (RFC 1950's algorithm); both also agree with zlib's own.
TEST(Png, ChecksumsMatchCheckValuesAndZlib) {
    const std::string check = "123456789", wiki = "Wikipedia";
    EXPECT_EQ(png::crc32(reinterpret_cast<const uint8_t *>(check.data()), check.size()), 0xcbf43926u);
    EXPECT_EQ(png::adler32(reinterpret_cast<const uint8_t *>(wiki.data()), wiki.size()), 0x11e60398u);
    std::mt19937 rng(7);
    Bytes data(100000);
    for (uint8_t &x : data) x = static_cast<uint8_t>(rng());
    EXPECT_EQ(png::crc32(data.data(), data.size()), ::crc32(0, data.data(), static_cast<uInt>(data.size())));
    EXPECT_EQ(png::adler32(data.data(), data.size()), ::adler32(1, data.data(), static_cast<uInt>(data.size())));
}

// Decodes with zlib to the same pixels: a 1×1 image, and 300×100 (90 100 bytes of
// scanlines: two stored deflate blocks, the first full at 65 535 bytes).
TEST(Png, ZlibDecodesTheSamePixels) {
    std::mt19937 rng(11);
    for (auto [w, h] : {std::pair{1, 1}, std::pair{300, 100}, std::pair{7, 3}}) {
        Bytes rgb(3 * static_cast<size_t>(w) * static_cast<size_t>(h));
        for (uint8_t &x : rgb) x = static_cast<uint8_t>(rng());
        const Bytes file = png::encode_rgb8(rgb, w, h);
        DecodedPng d;
        ASSERT_NO_THROW(d = decode_png(file)) << w << "x" << h;
        EXPECT_EQ(d.width, w);
        EXPECT_EQ(d.height, h);
        EXPECT_EQ(d.rgb, rgb);
    }
    EXPECT_THROW(png::encode_rgb8(Bytes(5), 1, 2), std::invalid_argument);
    EXPECT_THROW(png::encode_rgb8(Bytes(), 0, 1), std::invalid_argument);
}

// ====================================================================================
// Colour map
// ====================================================================================

// Ends and middle are matplotlib's entries 0, 128 and 255 rounded to 8 bits; lightness
// rises monotonically (viridis is designed so): relative luminance rises from each
// sixteenth of the map to the next, and between neighbouring steps never falls by more
// than 8-bit rounding can explain (kLuminanceSlack: one level of one channel in the dark
// end, ΔY ≈ 0.2126·Δ(linear R) ≤ 3e-4).
TEST(Viridis, PublishedEntriesAndMonotoneLuminance) {
    EXPECT_EQ(viridis(0.0), (Rgb{68, 1, 84}));      // (0.267004, 0.004874, 0.329415)
    EXPECT_EQ(viridis(128.0 / 255), (Rgb{33, 145, 140})); // (0.127568, 0.566949, 0.550556)
    EXPECT_EQ(viridis(1.0), (Rgb{253, 231, 37}));   // (0.993248, 0.906157, 0.143936)
    EXPECT_EQ(viridis(-1.0), viridis(0.0));
    EXPECT_EQ(viridis(2.0), viridis(1.0));
    double previous = -1;
    for (int k = 0; k <= 1020; ++k) {
        const double y = luminance(viridis(k / 1020.0));
        ASSERT_GE(y, previous - kLuminanceSlack) << "t = " << k / 1020.0;
        previous = y;
    }
    for (int k = 0; k < 16; ++k) ASSERT_LT(luminance(viridis(k / 16.0)), luminance(viridis((k + 1) / 16.0))) << k;
    EXPECT_GT(luminance(viridis(1.0)) - luminance(viridis(0.0)), 0.7);
}

// ====================================================================================
// Pictures
// ====================================================================================

// v = unit coordinate of a (linear in a): column i of the plot shows a at unit coordinate
// (i + ½)/W, so the colour bar runs from ½/W to (W − ½)/W and column i must be exactly
// viridis(i/(W − 1)), in every row. Then v = unit coordinate of b (a log axis): row j from
// the top shows unit 1 − (j + ½)/H and must be viridis(1 − j/(H − 1)): brighter upwards.
TEST(Preview, EveryPixelHasTheColourOfItsValue) {
    {
        const Preview p = render_preview(make_table(false, [](double a, double, double) { return a; }), {});
        ASSERT_GT(p.plot_w, 100);
        EXPECT_NEAR(p.value_lo, 0.5 / p.plot_w, 1e-12);
        EXPECT_NEAR(p.value_hi, 1 - 0.5 / p.plot_w, 1e-12);
        double previous = -1;
        for (int i = 0; i < p.plot_w; ++i) {
            const Rgb want = viridis(static_cast<double>(i) / (p.plot_w - 1));
            for (int j : {0, p.plot_h / 2, p.plot_h - 1})
                ASSERT_EQ(pixel(p.image.rgb, p.image.width, p.plot_x + i, p.plot_y + j), want) << i << ", " << j;
            const double y = luminance(want);
            ASSERT_GE(y, previous - kLuminanceSlack);
            previous = y;
        }
    }
    {
        const Preview p = render_preview(make_table(false, [](double, double b, double) { return b; }), {});
        for (int j = 0; j < p.plot_h; ++j)
            ASSERT_EQ(pixel(p.image.rgb, p.image.width, p.plot_x + p.plot_w / 3, p.plot_y + j),
                      viridis(1.0 - static_cast<double>(j) / (p.plot_h - 1)))
                << j;
    }
}

// Ticks are placed through the warp: on the log axis b ∈ [10⁻³, 1], 0.01 and 0.1 sit at
// unit coordinates 1/3 and 2/3; on the linear axis a ∈ [0, 1], 0.2 sits at 0.2 and no
// decade (0.01) crowds the end. The colour bar labels its ends.
TEST(Preview, TicksFollowTheAxisWarp) {
    const Preview p = render_preview(make_table(false, [](double a, double b, double) { return a + b; }), {});
    const PreviewTick *t01 = find_tick(p.y_ticks, "0.01"), *t1 = find_tick(p.y_ticks, "0.1");
    ASSERT_TRUE(t01 && t1) << "y ticks missing 0.01 or 0.1";
    EXPECT_NEAR(t01->pos, 1.0 / 3, 1e-12);
    EXPECT_NEAR(t1->pos, 2.0 / 3, 1e-12);
    ASSERT_TRUE(find_tick(p.x_ticks, "0.2"));
    EXPECT_NEAR(find_tick(p.x_ticks, "0.2")->pos, 0.2, 1e-12);
    EXPECT_FALSE(find_tick(p.x_ticks, "0.01"));
    ASSERT_TRUE(find_tick(p.x_ticks, "0") && find_tick(p.x_ticks, "1"));
    ASSERT_GE(p.bar_ticks.size(), 3u);
    EXPECT_EQ(p.bar_ticks[0].pos, 0.0);
    EXPECT_EQ(p.bar_ticks[1].pos, 1.0);
}

// The slice of a 3-D table: v = c (linear in c), so the slice's constant value names the
// slice. Default: middle node (6 − 1)/2 = 2, c = 4; #5 is c = 10; c = 7 lies between
// nodes 3 and 4 and is interpolated exactly.
TEST(Preview, SliceByNodeOrParameter) {
    const Table t = make_table(true, [](double, double, double c) { return 10 * c; });
    const Preview mid = render_preview(t, {});
    ASSERT_EQ(mid.slice.size(), 1u);
    EXPECT_EQ(mid.slice[0].node, 2);
    EXPECT_EQ(mid.slice[0].param, 4.0);
    EXPECT_NEAR(0.5 * (mid.value_lo + mid.value_hi), 4.0, 1e-9);
    EXPECT_NE(mid.slice_text.find("c = 4 (node 2 of 0-5)"), std::string::npos) << mid.slice_text;

    PreviewRequest r;
    r.slice = "c=#5";
    EXPECT_NEAR(0.5 * (render_preview(t, r).value_lo + render_preview(t, r).value_hi), 10.0, 1e-9);
    r.slice = " c = 7 ";
    const Preview seven = render_preview(t, r);
    EXPECT_NEAR(0.5 * (seven.value_lo + seven.value_hi), 7.0, 1e-9);
    EXPECT_EQ(seven.slice[0].node, -1);
    EXPECT_NE(seven.slice_text.find("c = 7 (between nodes 3 and 4)"), std::string::npos) << seven.slice_text;

    // Plot a × c instead: b is sliced (middle node 1 of 0-3, b = 0.01).
    r = {};
    r.plot_axes = {"a", "c"};
    const Preview ac = render_preview(t, r);
    EXPECT_EQ(ac.x_axis, 0u);
    EXPECT_EQ(ac.y_axis, 2);
    ASSERT_EQ(ac.slice.size(), 1u);
    EXPECT_EQ(ac.slice[0].axis, 1u);
    EXPECT_NEAR(ac.slice[0].param, 0.01, 1e-15);
}

TEST(Preview, BadRequestsSayWhatIsWrong) {
    const Table t = make_table(true, [](double a, double, double) { return a; });
    auto with = [&](const char *slice) {
        PreviewRequest r;
        r.slice = slice;
        return [=] { render_preview(t, r); };
    };
    expect_invalid(with("d=1"), "--slice: the table has no axis 'd' (its axes: a, b, c)");
    expect_invalid(with("a=0.5"), "axis 'a' is plotted");
    expect_invalid(with("c=11"), "--slice c=11: outside the axis range [0, 10]");
    expect_invalid(with("c=#6"), "node index must be #0 to #5");
    expect_invalid(with("c=#"), "node index must be #0 to #5");
    expect_invalid(with("c=abc"), "'abc' is not a number");
    expect_invalid(with("c"), "expected NAME=VALUE or NAME=#NODE");
    expect_invalid(with("c=1,c=2"), "axis 'c' given twice");
    PreviewRequest r;
    r.channel = "zz";
    expect_invalid([&] { render_preview(t, r); }, "no channel 'zz' (its channels: v)");
    r = {};
    r.plot_axes = {"a", "a"};
    expect_invalid([&] { render_preview(t, r); }, "x and y are both 'a'");
}

// A 1-D table is a strip.
TEST(Preview, OneDimensionalStrip) {
    Table t = make_table(false, [](double a, double, double) { return a; });
    t.axes.pop_back();
    t.values.resize(5);
    const Preview p = render_preview(t, {});
    EXPECT_EQ(p.y_axis, -1);
    EXPECT_TRUE(p.slice.empty());
    EXPECT_EQ(pixel(p.image.rgb, p.image.width, p.plot_x, p.plot_y + p.plot_h - 1), viridis(0.0));
}

// ====================================================================================
// The command line: inspect FILE --preview out.png
// ====================================================================================

// End to end: the PNG the executable writes decodes with zlib, has the size --json reports,
// and its plot shows the gradient; a bad request exits 2 and writes nothing.
TEST(InspectPreview, WritesADecodablePngAtomically) {
    const std::string dir = slut_test::temp_stem("preview");
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string table = dir + "/gradient.slut", out = dir + "/gradient.png";
    save_binary(make_table(true, [](double a, double, double) { return a; }), table);

    const auto r = slut_test::run_scatterlut("inspect --json " + table + " --preview " + out + " --slice c=#1");
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out).at("preview");
    EXPECT_EQ(j.at("file"), out);
    EXPECT_EQ(j.at("slice").at(0).at("axis"), "c");
    EXPECT_EQ(j.at("slice").at(0).at("node"), 1);
    DecodedPng png;
    ASSERT_NO_THROW(png = decode_png(read_all(out)));
    EXPECT_EQ(png.width, j.at("width").get<int>());
    EXPECT_EQ(png.height, j.at("height").get<int>());
    const int x0 = j.at("plot").at("x"), y0 = j.at("plot").at("y"), w = j.at("plot").at("width");
    const int h = j.at("plot").at("height");
    double previous = -1;
    for (int i = 0; i < w; ++i) {
        const Rgb c = pixel(png.rgb, png.width, x0 + i, y0 + h / 2);
        ASSERT_EQ(c, viridis(static_cast<double>(i) / (w - 1))) << "column " << i;
        ASSERT_GE(luminance(c), previous - kLuminanceSlack);
        previous = luminance(c);
    }

    // Text mode says where the picture went; a bad slice is exit 2 with the reason, no file.
    const auto text = slut_test::run_scatterlut("inspect " + table + " --preview " + dir + "/b.png --axes a,c");
    EXPECT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("preview         " + dir + "/b.png"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("slice: b = 0.01 (node 1 of 0-3)"), std::string::npos) << text.out;
    const auto bad = slut_test::run_scatterlut("inspect " + table + " --preview " + dir + "/bad.png --slice c=99");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--slice c=99: outside the axis range [0, 10]"), std::string::npos) << bad.err;
    std::vector<std::string> names;
    for (const auto &e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"b.png", "gradient.png", "gradient.slut"})); // no temp, no bad.png
    EXPECT_EQ(slut_test::run_scatterlut("inspect " + table + " --slice c=1").exit_code, 2); // needs --preview
    std::filesystem::remove_all(dir);
}
