// The program binary cache (host/src/program_cache.hpp): a second Device loads the binary
// saved after the first one's kernels ran, and every kind of damaged entry falls back to a
// build from source that computes the same table. The reference for "the same table" is
// the table computed from a fresh source build, itself checked against the independent
// host quadrature (slut_gs_quadrature, refine = 3) so that two equally wrong programs
// cannot pass.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "generate_airlight.hpp"
#include "opencl_device.hpp"
#include "scatterlut/io.hpp"

extern "C" {
#include "slut_airlight.h"
}

namespace fs = std::filesystem;
using scatterlut::Device;
using scatterlut::ProgramOrigin;

namespace {

// A fresh, empty cache directory for each test ($XDG_CACHE_HOME/scatterlut). XDG_CACHE_HOME
// is set once per process and only our subdirectory is cleared: PoCL keeps its own kernel
// cache under $XDG_CACHE_HOME/pocl and fixes that path at its first build.
class ProgramCacheTest : public ::testing::Test {
protected:
    void SetUp() override {
        static const fs::path root = [] {
            const fs::path r = fs::temp_directory_path() / ("slut_cache_test_" + std::to_string(::getpid()));
            fs::remove_all(r);
            fs::create_directories(r);
            ::setenv("XDG_CACHE_HOME", r.c_str(), 1);
            return r;
        }();
        static const struct RemoveAtExit {
            fs::path p;
            ~RemoveAtExit() { std::error_code ec; fs::remove_all(p, ec); }
        } remove_at_exit{root};
        root_ = root;
        fs::remove_all(root_ / "scatterlut");
        ::unsetenv("SCATTERLUT_PROGRAM_CACHE");
        scatterlut::AirlightPlan plan;
        plan.n_u = 19;
        plan.n_w = 13;
        layout_ = scatterlut::make_airlight_table_layout(plan);
    }
    void TearDown() override { fs::remove_all(root_ / "scatterlut"); }

    std::vector<double> generate(Device &device) { return scatterlut::integrate_airlight_ln_gs(device, layout_); }

    std::vector<fs::path> entries() const {
        std::vector<fs::path> out;
        if (fs::exists(root_ / "scatterlut"))
            for (const auto &e : fs::directory_iterator(root_ / "scatterlut")) out.push_back(e.path());
        return out;
    }

    // The worst relative error against the host quadrature, over every node.
    double worst_error(const std::vector<double> &ln_gs) const {
        const slut_axis &au = layout_.axes[0].map, &aw = layout_.axes[1].map;
        double worst = 0;
        for (int j = 0; j < aw.count; ++j)
            for (int i = 0; i < au.count; ++i) {
                const double ref = slut_gs_quadrature(slut_axis_node(&au, i), slut_axis_node(&aw, j), 3.0);
                worst = std::max(worst, std::fabs(std::exp(ln_gs[static_cast<size_t>(j * au.count + i)]) - ref) / ref);
            }
        return worst;
    }

    fs::path root_;
    scatterlut::Table layout_;
};

std::vector<uint8_t> read_all(const fs::path &p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_all(const fs::path &p, const std::vector<uint8_t> &bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

uint64_t get_u64(const std::vector<uint8_t> &b, size_t pos) {
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(b[pos + static_cast<size_t>(i)]) << (8 * i);
    return v;
}

void put_u64(std::vector<uint8_t> &b, size_t pos, uint64_t v) {
    for (int i = 0; i < 8; ++i) b[pos + static_cast<size_t>(i)] = static_cast<uint8_t>(v >> (8 * i));
}

} // namespace

// Source build → entry stored after the run → the next Device loads it, same values.
// 1e-12: the sweep's accuracy (measured ~1e-14) with margin.
TEST_F(ProgramCacheTest, SecondDeviceLoadsTheStoredBinary) {
    std::vector<double> first;
    {
        Device device("");
        first = generate(device);
        EXPECT_EQ(device.program_origin("airlight_F.cl"), ProgramOrigin::Source);
    }
    EXPECT_LE(worst_error(first), 1e-12);
    ASSERT_EQ(entries().size(), 1u);
    Device device("");
    EXPECT_EQ(generate(device), first); // bitwise: same compiled code, deterministic
    EXPECT_EQ(device.program_origin("airlight_F.cl"), ProgramOrigin::Cache);
}

// Each damage is detected or rejected by the driver; the fallback computes the same table
// and re-stores a good entry.
TEST_F(ProgramCacheTest, DamagedEntriesFallBackToASourceBuild) {
    std::vector<double> reference;
    {
        Device device("");
        reference = generate(device);
    }
    ASSERT_LE(worst_error(reference), 1e-12);
    ASSERT_EQ(entries().size(), 1u);
    const fs::path entry = entries()[0];
    const std::vector<uint8_t> good = read_all(entry);

    // Layout: magic(8) | u64 id_len | id | u64 bin_len | bin | u64 FNV-1a of all before.
    const size_t id_len = static_cast<size_t>(get_u64(good, 8));
    const size_t bin_pos = 16 + id_len + 8;
    const size_t bin_len = static_cast<size_t>(get_u64(good, 16 + id_len));
    ASSERT_EQ(bin_pos + bin_len + 8, good.size());

    struct Damage {
        const char *name, *log;
        std::vector<uint8_t> bytes;
    };
    std::vector<Damage> damages;
    {
        std::vector<uint8_t> b = good;
        b[bin_pos + bin_len / 2] ^= 0x5a; // a flipped byte in the binary
        damages.push_back({"flipped byte", "checksum mismatch", b});
    }
    damages.push_back({"truncated", "truncated", std::vector<uint8_t>(good.begin(), good.begin() + static_cast<long>(good.size() / 2))});
    damages.push_back({"not an entry", "not a scatterlut program cache entry", std::vector<uint8_t>(100, 0x42)});
    {
        // A well-formed entry (right key, right checksum) whose binary is garbage: only the
        // driver can tell, and must.
        std::vector<uint8_t> b = good;
        for (size_t i = 0; i < bin_len; ++i) b[bin_pos + i] = static_cast<uint8_t>(i * 131u + 7u);
        put_u64(b, bin_pos + bin_len, scatterlut::fnv1a64(b.data(), bin_pos + bin_len));
        damages.push_back({"garbage binary", "driver rejected", b});
    }
    {
        std::vector<uint8_t> b = good;
        b[16] ^= 0x01; // first byte of the key text: another key
        put_u64(b, bin_pos + bin_len, scatterlut::fnv1a64(b.data(), bin_pos + bin_len));
        damages.push_back({"other key", "key mismatch", b});
    }
    for (const Damage &d : damages) {
        SCOPED_TRACE(d.name);
        write_all(entry, d.bytes);
        std::vector<double> got;
        ::testing::internal::CaptureStderr();
        {
            Device device("");
            got = generate(device);
            EXPECT_EQ(device.program_origin("airlight_F.cl"), ProgramOrigin::Source);
        }
        const std::string log = ::testing::internal::GetCapturedStderr();
        EXPECT_NE(log.find(d.log), std::string::npos) << log;
        EXPECT_NE(log.find("building from source"), std::string::npos) << log;
        EXPECT_EQ(got, reference);
        // The fallback stored a good entry again.
        Device device("");
        EXPECT_EQ(generate(device), reference);
        EXPECT_EQ(device.program_origin("airlight_F.cl"), ProgramOrigin::Cache);
    }
}

// SCATTERLUT_PROGRAM_CACHE=0: nothing read, nothing written.
TEST_F(ProgramCacheTest, DisabledByEnvironment) {
    ::setenv("SCATTERLUT_PROGRAM_CACHE", "0", 1);
    Device device("");
    const std::vector<double> v = generate(device);
    EXPECT_EQ(device.program_origin("airlight_F.cl"), ProgramOrigin::Source);
    EXPECT_TRUE(entries().empty());
    EXPECT_LE(worst_error(v), 1e-12);
    ::unsetenv("SCATTERLUT_PROGRAM_CACHE");
}
