// The airlight_rational table as a kind (host/src/kinds/airlight_rational_kind.cpp,
// kernels/airlight_rational.cl; docs/FORMAT.md): the kernel on the real OpenCL device equals
// the node function in double; `plan` lists the table wherever airlight_F is planned for an
// isotropic medium, at the radiance target over 2G − 1; `generate --format all` writes it in
// the three formats, which read back (the library; OpenImageIO's oiiotool where installed);
// `validate` and `inspect` handle it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "generate_airlight_rational.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight_rational.hpp"
#include "scatterlut/io.hpp"

extern "C" {
#include "slut_airlight_rational.h"
}

namespace {

using slut_test::RunResult;

std::string write_scene(const std::string &tag, const std::string &text) {
    const std::string path = slut_test::temp_stem(tag) + ".toml";
    std::ofstream(path) << text;
    return path;
}

const nlohmann::json *table_of(const nlohmann::json &plan, const std::string &stem) {
    for (const auto &t : plan.at("tables"))
        if (t.at("file_stem") == stem) return &t;
    return nullptr;
}

std::set<std::string> stems_of(const nlohmann::json &plan) {
    std::set<std::string> stems;
    for (const auto &t : plan.at("tables")) stems.insert(t.at("file_stem").get<std::string>());
    return stems;
}

} // namespace

// Every node of a small table (the corners and both edges included) from the device (PoCL here)
// against slut_airlight_rational_node compiled for the host, both in double: the same function
// on the same arguments, so to a few ulps (libm and the device's exp, atan2 may differ).
TEST(AirlightRationalKind, DeviceNodesEqualTheNodeFunction) {
    scatterlut::Device device("");
    scatterlut::AirlightRationalPlan plan;
    plan.n_m = 41;
    plan.n_t = 37;
    plan.storage = scatterlut::Storage::F64;
    const scatterlut::Table t = scatterlut::generate_airlight_rational_table(device, plan, scatterlut::Provenance{});
    ASSERT_EQ(t.values.size(), static_cast<size_t>(plan.n_m) * plan.n_t);
    const slut_axis &am = t.axes[0].map, &at = t.axes[1].map;
    double worst = 0;
    for (int j = 0; j < at.count; ++j)
        for (int i = 0; i < am.count; ++i) {
            const double host = slut_airlight_rational_node(slut_axis_node(&am, i), slut_axis_node(&at, j), 1.0);
            const double got = t.values[static_cast<size_t>(j) * am.count + i];
            const double err = std::fabs(got - host) / host;
            ASSERT_LE(err, 1e-14) << "node (" << i << ", " << j << ")";
            worst = std::max(worst, err);
        }
    std::printf("device vs host node function, %d nodes: max rel %.2e\n", am.count * at.count, worst);
    EXPECT_GE(t.accuracy.integration_max_rel, 0.0);
    EXPECT_LE(t.accuracy.integration_max_rel, 1e-12);
    EXPECT_GT(t.accuracy.sampling_max_rel, 0.0);
    EXPECT_EQ(t.accuracy.storage_max_rel, 0.0); // f64
    // The generator's independent measurement (validate's) on every node.
    std::vector<scatterlut::NodeIndex> every;
    for (size_t j = 0; j < static_cast<size_t>(at.count); ++j)
        for (size_t i = 0; i < static_cast<size_t>(am.count); ++i) {
            scatterlut::NodeIndex p{};
            p[0] = i;
            p[1] = j;
            every.push_back(p);
        }
    const double independent = scatterlut::measure_airlight_rational_integration(
        scatterlut::AirlightRationalTable(t), every, scatterlut::IntegrationReference::IndependentGaussKronrod);
    std::printf("device nodes vs Boost.Math (long double): max rel %.2e\n", independent);
    EXPECT_LE(independent, 1e-12);
}

// `plan`: airlight_rational beside airlight_F for a viewer inside an isotropic medium, at the
// strictest medium's error over 2G − 1 (G = SLUT_AIRLIGHT_RATIONAL_GAIN), reached; not for an
// anisotropic medium, nor for a medium seen from outside.
TEST(AirlightRationalKind, PlannedWhereverTheIsotropicAirlightIs) {
    const std::string fog = write_scene(
        "rational_fog",
        "name = \"fog\"\n[accuracy]\nrelative_error = 0.01\n[[medium]]\nname = \"fog\"\nsigma_s_per_m = 0.04\n"
        "sigma_a_per_m = 0.002\nviewer_inside = true\nrelative_error = 0.003\n[[medium]]\nname = \"haze\"\n"
        "sigma_s_per_m = 0.01\nsigma_a_per_m = 0\nviewer_inside = true\n[[light]]\nname = \"lamp\"\ntype = \"point\"\n"
        "intensity_W_per_sr = 100\ndistance_m = [1, 100]\n");
    const RunResult r = slut_test::run_scatterlut("plan --json --scene " + fog);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json plan = nlohmann::json::parse(r.out);
    EXPECT_EQ(stems_of(plan), (std::set<std::string>{"airlight_F", "airlight_rational"}));
    const nlohmann::json *t = table_of(plan, "airlight_rational");
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->at("kind"), "airlight_rational");
    EXPECT_NEAR(t->at("target_rel").get<double>(), 0.003 / (2 * SLUT_AIRLIGHT_RATIONAL_GAIN - 1), 1e-15);
    EXPECT_TRUE(t->at("reached").get<bool>()) << t->at("verdict");
    EXPECT_LE(t->at("predicted_max_rel").get<double>(), t->at("target_rel").get<double>());
    EXPECT_LE(t->at("integration_max_rel").get<double>(), 1e-12);
    EXPECT_EQ(t->at("requested_by").size(), 2u); // fog and haze, as airlight_F's
    ASSERT_EQ(t->at("axes").size(), 2u);
    for (const auto &a : t->at("axes")) {
        EXPECT_EQ(a.at("warp"), "linear");
        EXPECT_EQ(a.at("min").get<double>(), 0.0);
        EXPECT_EQ(a.at("max").get<double>(), 1.0);
    }
    EXPECT_EQ(t->at("axes")[0].at("name"), "x_m");
    EXPECT_EQ(t->at("axes")[1].at("name"), "x_t");

    const std::string forward = write_scene(
        "rational_forward",
        "name = \"forward\"\n[[medium]]\nname = \"fog\"\nsigma_s_per_m = 0.04\nsigma_a_per_m = 0.002\n"
        "viewer_inside = true\nphase_g = 0.8\n[[medium]]\nname = \"wax\"\nsigma_s_per_m = 250\nsigma_a_per_m = 1\n"
        "viewer_inside = false\nthick = true\n[[light]]\nname = \"lamp\"\ntype = \"point\"\nintensity_W_per_sr = 100\n"
        "distance_m = [1, 100]\nmedia = [\"fog\"]\n[[light]]\nname = \"flame\"\ntype = \"point\"\n"
        "intensity_W_per_sr = 0.1\ndistance_m = [0.005, 0.05]\nmedia = [\"wax\"]\n");
    const RunResult f = slut_test::run_scatterlut("plan --json --scene " + forward);
    ASSERT_EQ(f.exit_code, 0) << f.err;
    const std::set<std::string> stems = stems_of(nlohmann::json::parse(f.out));
    EXPECT_EQ(stems, (std::set<std::string>{"airlight_Fg_g0.8", "near_light_E3"}));
    std::filesystem::remove(fog);
    std::filesystem::remove(forward);
}

// The default scene with --format all: airlight_rational.{slut,exr,ktx2} beside the others, each
// read back (the binary and the EXR by the library, equal values; the KTX2's header), validated
// and inspected; OpenImageIO reads the EXR where oiiotool is installed.
TEST(AirlightRationalKind, DefaultTablesInEveryFormatReadBack) {
    const std::string dir = slut_test::temp_stem("rational_all");
    std::filesystem::remove_all(dir);
    const RunResult gen = slut_test::run_scatterlut("generate --format all --out " + dir);
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
    for (const char *ext : {".slut", ".exr", ".ktx2"})
        EXPECT_TRUE(std::filesystem::exists(dir + "/airlight_rational" + ext)) << ext;

    const scatterlut::Table bin = scatterlut::load_table(dir + "/airlight_rational.slut");
    const scatterlut::Table exr = scatterlut::load_table(dir + "/airlight_rational.exr");
    EXPECT_EQ(bin.kind, scatterlut::kKindAirlightRational);
    EXPECT_EQ(bin.quantity_version, scatterlut::kAirlightRationalQuantityVersion);
    EXPECT_EQ(bin.values, exr.values);
    const scatterlut::AirlightRationalTable table(bin); // the loader's checks
    EXPECT_GE(table.m_count(), 8);
    EXPECT_GE(table.t_count(), 8);
    EXPECT_EQ(bin.storage, scatterlut::Storage::F32);
    // KTX2: the identifier, VK_FORMAT_R32_SFLOAT, width × height = x_m × x_t nodes.
    {
        std::ifstream in(dir + "/airlight_rational.ktx2", std::ios::binary);
        std::vector<unsigned char> head(48);
        in.read(reinterpret_cast<char *>(head.data()), 48);
        ASSERT_EQ(in.gcount(), 48);
        const unsigned char id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
        EXPECT_TRUE(std::equal(id, id + 12, head.begin()));
        auto u32 = [&](size_t at) {
            return head[at] | (head[at + 1] << 8) | (head[at + 2] << 16) | (static_cast<uint32_t>(head[at + 3]) << 24);
        };
        EXPECT_EQ(u32(12), 100u); // vkFormat
        EXPECT_EQ(u32(20), static_cast<uint32_t>(table.m_count()));
        EXPECT_EQ(u32(24), static_cast<uint32_t>(table.t_count()));
        EXPECT_EQ(u32(28), 0u); // a 2-D texture
    }

    const RunResult v = slut_test::run_scatterlut("validate --json " + dir + "/airlight_rational.slut " + dir +
                                                  "/airlight_rational.exr");
    EXPECT_EQ(v.exit_code, 0) << v.out << v.err;
    for (const nlohmann::json &line : slut_test::json_lines(v.out)) {
        EXPECT_EQ(line.at("status"), "PASS") << line.dump();
        EXPECT_EQ(line.at("kind"), "airlight_rational");
    }
    const RunResult all = slut_test::run_scatterlut("validate " + dir);
    EXPECT_EQ(all.exit_code, 0) << all.out << all.err;

    const RunResult i = slut_test::run_scatterlut("inspect --json " + dir + "/airlight_rational.exr");
    ASSERT_EQ(i.exit_code, 0) << i.err;
    const nlohmann::json info = nlohmann::json::parse(i.out);
    EXPECT_EQ(info.at("kind"), "airlight_rational");
    EXPECT_EQ(info.at("channels")[0].at("name"), "Hn");

    if (std::system("command -v oiiotool > /dev/null 2>&1") == 0) {
        const std::string out = slut_test::temp_stem("rational_oiio") + ".txt";
        ASSERT_EQ(std::system(("oiiotool --info -v " + dir + "/airlight_rational.exr > " + out + " 2>&1").c_str()), 0);
        std::ifstream in(out);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::smatch size;
        ASSERT_TRUE(std::regex_search(text, size, std::regex(R"(airlight_rational\.exr : +(\d+) x +(\d+), 1 channel)")))
            << text;
        EXPECT_EQ(std::stoi(size[1]), table.m_count());
        EXPECT_EQ(std::stoi(size[2]), table.t_count());
        EXPECT_NE(text.find("float"), std::string::npos) << text;
        EXPECT_NE(text.find("scatterlut.kind: \"airlight_rational\""), std::string::npos) << text;
        std::filesystem::remove(out);
    } else {
        std::printf("oiiotool not installed: the EXR read by the library alone\n");
    }
    std::filesystem::remove_all(dir);
}
