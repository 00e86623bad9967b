// Tests of the table files (docs/FORMAT.md): the table's names and checks, storage rounding,
// checksums, binary round trips and determinism, loading errors and atomic writes. The hostile
// binary files: test_io_binary_hostile.cpp; EXR: test_io_exr.cpp; the command line on hostile
// files: test_io_cli_hostile.cpp (one test executable, test_io).
//
// References: IEEE 754 binary16/binary32 (round to nearest, ties to even) checked
// exhaustively over all binary16 numbers and the midpoints between them; the byte
// layout as documented in docs/FORMAT.md, re-implemented in io_test_support.hpp (record walker
// and FNV-1a-64) so that a file built or patched by the test is judged by the document,
// not by the library's own encoder.

#include "io_test_support.hpp"

// ====================================================================================
// table.cpp
// ====================================================================================

TEST(TableNames, RoundTrip) {
    for (Storage s : {Storage::F16, Storage::F32, Storage::F64}) {
        Storage back{};
        ASSERT_TRUE(storage_from_string(to_string(s), &back));
        EXPECT_EQ(back, s);
    }
    EXPECT_EQ(storage_bytes(Storage::F16), 2u);
    EXPECT_EQ(storage_bytes(Storage::F32), 4u);
    EXPECT_EQ(storage_bytes(Storage::F64), 8u);
    for (Encoding e : {Encoding::Linear, Encoding::Log}) {
        Encoding back{};
        ASSERT_TRUE(encoding_from_string(to_string(e), &back));
        EXPECT_EQ(back, e);
    }
    const char *names[] = {"linear", "log", "log1p", "asinh_cot", "sqrt1p", "loglin", "nl_qodds", "asinh_cot_peak"};
    static_assert(sizeof(names) / sizeof(names[0]) == SLUT_WARP_COUNT, "one name per warp id");
    for (int w = 0; w < SLUT_WARP_COUNT; ++w) {
        EXPECT_STREQ(warp_name(w), names[w]);
        int back = -1;
        ASSERT_TRUE(warp_from_name(names[w], &back));
        EXPECT_EQ(back, w);
    }
    EXPECT_FALSE(warp_from_name("cubic", nullptr));
    EXPECT_FALSE(storage_from_string("f8", nullptr));
    EXPECT_FALSE(encoding_from_string("sqrt", nullptr));
}

TEST(TableIndex, AxisZeroFastestChannelFastestOfAll) {
    const Table t = make_table(3, Storage::F64); // counts 7, 5, 4; 2 channels
    EXPECT_EQ(t.node_count(), 7u * 5u * 4u);
    const size_t node[3] = {2, 3, 1};
    EXPECT_EQ(t.index(node), ((1u * 5u + 3u) * 7u + 2u) * 2u);
    t.check_consistent();
}

TEST(TableCheck, ClearMessages) {
    auto expect = [](Table t, const std::string &needle) {
        try {
            t.check_consistent();
            ADD_FAILURE() << "no exception; expected '" << needle << "'";
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    Table t = make_table(2, Storage::F32);
    { Table u = t; u.values.pop_back(); expect(u, "values holds 69 numbers, expected 70"); }
    { Table u = t; u.axes[0].map.min = 60; expect(u, "min 60 must be less than max 50"); }
    { Table u = t; u.axes[1].map.count = 1; expect(u, "axis 1 ('w'): count 1 is invalid"); }
    { Table u = t; u.axes[0].map.warp = SLUT_WARP_COUNT; expect(u, "unknown warp id " + std::to_string(SLUT_WARP_COUNT)); }
    { Table u = t; u.axes[1].map.warp = SLUT_WARP_ASINH_COT_PEAK; expect(u, "warp 'asinh_cot_peak' needs 0 < min, max <= pi/2 and scale > 0"); }
    { Table u = t; u.axes[0].map.scale = 0; expect(u, "warp 'log1p' needs scale > 0"); }
    { Table u = t; u.axes[1].map.min = 0; expect(u, "warp 'asinh_cot' needs min > 0"); }
    { Table u = t; u.axes[0].map.max = INFINITY; expect(u, "is not finite"); }
    { Table u = t; u.values[3] = NAN; expect(u, "value 3 (node (1, 0), channel 'ln_G') is not finite"); }
    { Table u = t; u.channels[1].name = "F"; expect(u, "channel name 'F' appears twice"); }
    { Table u = t; u.axes.clear(); expect(u, "no axes"); }
    { Table u = t; u.axes.resize(9, t.axes[0]); expect(u, "at most 8"); }
}

// ====================================================================================
// Storage rounding
// ====================================================================================

// Reference: IEEE 754 binary16. Every finite half converts back to itself; every
// midpoint between neighbours rounds to the one with an even fraction, and the doubles
// just either side of it to the nearer neighbour. Covers subnormals (h < 0x400), the
// normal/subnormal boundary, and overflow (midpoint 65520 between 65504 and 2^16 → inf).
TEST(F16Conversion, ExhaustiveRoundToNearestEven) {
    for (uint32_t h = 0; h < 0x7c00; ++h) {
        const double v = double_from_f16(static_cast<uint16_t>(h));
        ASSERT_EQ(f16_from_double(v), h) << h;
        ASSERT_EQ(f16_from_double(-v), h | 0x8000u) << h;
        const double next = h + 1 < 0x7c00 ? double_from_f16(static_cast<uint16_t>(h + 1)) : 65536.0;
        const double mid = 0.5 * (v + next); // exact in double
        const uint32_t even = (h & 1u) ? h + 1 : h;
        ASSERT_EQ(f16_from_double(mid), even) << "midpoint above " << h;
        ASSERT_EQ(f16_from_double(std::nextafter(mid, 0.0)), h) << h;
        ASSERT_EQ(f16_from_double(std::nextafter(mid, INFINITY)), h + 1) << h;
    }
    EXPECT_EQ(double_from_f16(0x7bff), 65504.0);
    EXPECT_EQ(double_from_f16(0x0001), std::ldexp(1.0, -24));
    EXPECT_EQ(double_from_f16(0x0400), std::ldexp(1.0, -14));
    EXPECT_EQ(f16_from_double(65520.0), 0x7c00);
    EXPECT_EQ(f16_from_double(1e300), 0x7c00);
    EXPECT_EQ(f16_from_double(-INFINITY), 0xfc00);
    EXPECT_TRUE(std::isnan(double_from_f16(f16_from_double(NAN))));
    EXPECT_EQ(f16_from_double(std::ldexp(1.0, -25)), 0x0000); // tie with 0 → even 0
    EXPECT_EQ(f16_from_double(1e-300), 0x0000);
    EXPECT_EQ(f16_from_double(std::numeric_limits<double>::denorm_min()), 0x0000);
    EXPECT_EQ(f16_from_double(-0.0), 0x8000);
    EXPECT_TRUE(std::isinf(double_from_f16(0x7c00)));
}

TEST(F32Rounding, MatchesFloatCastAndOverflowIsExplicit) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> mant(-1.0, 1.0);
    std::uniform_int_distribution<int> ex(-140, 127);
    for (int i = 0; i < 100000; ++i) {
        const double x = std::ldexp(mant(rng), ex(rng));
        ASSERT_EQ(round_to_storage(x, Storage::F32), static_cast<double>(static_cast<float>(x))) << x;
    }
    const double fmax = FLT_MAX;
    EXPECT_EQ(round_to_storage(std::nextafter(0x1.ffffffp127, 0.0), Storage::F32), fmax);
    EXPECT_TRUE(std::isinf(round_to_storage(0x1.ffffffp127, Storage::F32))); // tie → even (2^128)
    EXPECT_TRUE(std::isinf(round_to_storage(-1e300, Storage::F32)));
}

// Expected: f64 exact (0); f32 relative error ≤ 2^-24 (half an ulp) on linear channels;
// f16 ≤ 2^-11 for values in the normal range. Values spread over many binades reach
// close to the bound, so also check it is not trivially small (> bound/4).
TEST(StorageRounding, MaxRelMatchesHalfUlpBounds) {
    Table t = make_table(2, Storage::F64);
    for (Channel &c : t.channels) c.encoding = Encoding::Linear;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(1.0, 1000.0);
    for (double &v : t.values) v = u(rng);
    EXPECT_EQ(storage_rounding_max_rel(t, Storage::F64), 0.0);
    const double r32 = storage_rounding_max_rel(t, Storage::F32);
    EXPECT_LE(r32, std::ldexp(1.0, -24));
    EXPECT_GT(r32, std::ldexp(1.0, -26));
    const double r16 = storage_rounding_max_rel(t, Storage::F16);
    EXPECT_LE(r16, std::ldexp(1.0, -11));
    EXPECT_GT(r16, std::ldexp(1.0, -13));
    t.values[5] = 1e5; // beyond f16
    EXPECT_TRUE(std::isinf(storage_rounding_max_rel(t, Storage::F16)));
    t.values[5] = NAN;
    EXPECT_THROW(storage_rounding_max_rel(t, Storage::F32), std::invalid_argument);
}

// Log channel: quantity q = exp(stored), so the relative error on q is |exp(r − v) − 1|,
// about |v|·2^-24 for f32, not 2^-24: computed independently here.
TEST(StorageRounding, LogChannelErrorIsOnTheQuantity) {
    Table t = make_table(1, Storage::F64);
    double expected = 0;
    for (size_t i = 0; i < t.values.size(); ++i) {
        const double v = t.values[i];
        const double r = static_cast<double>(static_cast<float>(v));
        const double rel = t.channels[i % 2].encoding == Encoding::Log ? std::fabs(std::exp(r) / std::exp(v) - 1.0)
                                                                       : std::fabs(r - v) / std::fabs(v);
        expected = std::max(expected, rel);
    }
    EXPECT_NEAR(storage_rounding_max_rel(t, Storage::F32), expected, 1e-3 * expected);
}

// Reference: the published FNV-1a-64 test vectors (docs/FORMAT.md §2.5), and the
// test's own implementation from the document, continued over two pieces.
TEST(Checksum, Fnv1a64Vectors) {
    EXPECT_EQ(fnv1a64("", 0), 0xcbf29ce484222325ull);
    EXPECT_EQ(fnv1a64("a", 1), 0xaf63dc4c8601ec8cull);
    EXPECT_EQ(fnv1a64("foobar", 6), 0x85944171f73967e8ull);
    EXPECT_EQ(fnv1a64("bar", 3, fnv1a64("foo", 3)), fnv1a64("foobar", 6));
    const uint8_t bytes[] = {0, 1, 2, 255, 128};
    EXPECT_EQ(fnv1a64(bytes, 5), doc_fnv1a64(bytes, 5));
}

// ====================================================================================
// Binary round trips and determinism
// ====================================================================================

TEST(Binary, RoundTripAllDimensionsAndStorages) {
    for (size_t dims = 1; dims <= 4; ++dims) {
        for (Storage s : {Storage::F16, Storage::F32, Storage::F64}) {
            SCOPED_TRACE(std::to_string(dims) + "-D " + to_string(s));
            const Table t = make_table(dims, s);
            const Bytes b = encode_binary(t);
            const Table back = decode_binary(b.data(), b.size(), "mem");
            expect_same_metadata(t, back);
            expect_values_rounded(t, back);
            // Deterministic, and a loaded table re-encodes to the same bytes.
            EXPECT_EQ(encode_binary(t), b);
            EXPECT_EQ(encode_binary(back), b);
            // Payload 64-byte aligned (FORMAT.md §2.1).
            EXPECT_EQ((48 + get_u64(&b[16])) % 64, 0u);
        }
    }
}

TEST(Binary, SaveLoadFilesByteIdentical) {
    TempDir dir;
    const Table t = make_table(3, Storage::F32);
    save_binary(t, dir.path + "/a.slut");
    save_binary(t, dir.path + "/b.slut");
    EXPECT_EQ(read_all(dir.path + "/a.slut"), read_all(dir.path + "/b.slut"));
    const Table back = load_binary(dir.path + "/a.slut");
    expect_same_metadata(t, back);
    const Table any = load_table(dir.path + "/a.slut");
    expect_values_rounded(t, any);
    EXPECT_EQ(dir.entries().size(), 2u); // no temp files left
}

TEST(Binary, WriterRefusesWhatTheFormatCannotHold) {
    Table t = make_table(2, Storage::F16);
    t.values[0] = 70000.0; // > 65504
    try {
        encode_binary(t);
        ADD_FAILURE();
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("overflows f16"), std::string::npos) << e.what();
    }
    Table u = make_table(1, Storage::F32);
    u.kind = std::string(300, 'k');
    EXPECT_THROW(encode_binary(u), std::invalid_argument);
    Table v = make_table(1, Storage::F32);
    for (int i = 0; i < 16; ++i) v.channels.push_back(Channel{"c" + std::to_string(i), "", Encoding::Linear});
    v.values.assign(v.node_count() * v.channels.size(), 1.0);
    EXPECT_THROW(encode_binary(v), std::invalid_argument);
}

TEST(LoadTable, FileErrors) {
    TempDir dir;
    expect_load_error([&] { load_table(dir.path + "/missing.slut"); }, "cannot open for reading");
    expect_load_error([&] { load_table(dir.path); }, "is a directory");
    write_all(dir.path + "/junk.bin", Bytes{'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd'});
    expect_load_error([&] { load_table(dir.path + "/junk.bin"); }, "junk.bin: not a scatterlut binary table");
    write_all(dir.path + "/empty.slut", Bytes{});
    expect_load_error([&] { load_binary(dir.path + "/empty.slut"); }, "empty.slut: truncated: the file is empty");
}

// ====================================================================================
// Atomic writes
// ====================================================================================

TEST(AtomicWrite, MissingOrInvalidDirectoryThrowsAndLeavesNothing) {
    TempDir dir;
    const Table t = make_table(1, Storage::F32);
    EXPECT_THROW(save_binary(t, dir.path + "/no/such/dir/t.slut"), std::system_error);
    write_all(dir.path + "/plainfile", Bytes{1});
    EXPECT_THROW(save_binary(t, dir.path + "/plainfile/t.slut"), std::system_error);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"plainfile"});
    if (::geteuid() != 0) { // root writes anywhere
        const std::string ro = dir.path + "/ro";
        ASSERT_EQ(::mkdir(ro.c_str(), 0555), 0);
        EXPECT_THROW(save_binary(t, ro + "/t.slut"), std::system_error);
        ::chmod(ro.c_str(), 0755);
    }
}

TEST(AtomicWrite, FailedWriteLeavesPreviousFileIntact) {
    TempDir dir;
    const std::string path = dir.path + "/t.slut";
    const Table small = make_table(1, Storage::F32);
    save_binary(small, path);
    const Bytes before = read_all(path);

    // 1. The table cannot be encoded: nothing is written.
    Table bad = make_table(2, Storage::F16);
    bad.values[0] = 1e6;
    EXPECT_THROW(save_binary(bad, path), std::invalid_argument);
    EXPECT_EQ(read_all(path), before);

    // 2. The write itself fails half-way (file size limit → EFBIG).
    const Table big = make_table(4, Storage::F64); // ~8 KB, beyond the limit below
    ASSERT_GT(encode_binary(big).size(), 4096u + 1024u);
    struct rlimit old_limit;
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old_limit), 0);
    auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    struct rlimit low = old_limit;
    low.rlim_cur = 4096;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &low), 0);
    bool threw = false;
    try {
        save_binary(big, path);
    } catch (const std::system_error &e) {
        threw = true;
        EXPECT_NE(std::string(e.what()).find("previous file left intact"), std::string::npos) << e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old_limit);
    std::signal(SIGXFSZ, old_handler);
    EXPECT_TRUE(threw);
    EXPECT_EQ(read_all(path), before);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"t.slut"}); // temp removed

    // 3. And a successful write replaces it.
    save_binary(big, path);
    EXPECT_EQ(read_all(path), encode_binary(big));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"t.slut"});
}
