// Hostile but fair input through the built `scatterlut` executable (test_hostile.cpp): physical
// extremes (the airlight's limits, nanometre distances, F at small v) and corrupt-but-consistent
// table files. Part of the test_hostile executable.

#include "hostile_test_support.hpp"

// ------------------------------------------------------------------ 8, 10: physical extremes

TEST(HostileExtremes, AirlightGivesTheLimitOrANoteNeverASilentNull) {
    const std::string q = R"({"quantity":"airlight","sigma_a":0,"gamma":1,"length":2,)";
    const std::string input =
        std::string(R"({"quantity":"airlight","sigma_s":1,"sigma_a":4e153,"intensity":1,"distance":2.8e191,"gamma":1.5e-144,"length":"inf"})") + "\n" +
        q + R"("sigma_s":1e300,"intensity":1e308,"distance":1})" + "\n" +      // e^{-1e300}: 0
        q + R"("sigma_s":1e300,"intensity":1e308,"distance":1e-300})" + "\n" + // beyond the double range
        q + R"("sigma_s":1e-300,"intensity":1e-300,"distance":1e-300})" + "\n" +
        R"({"quantity":"near_light","sigma_s":1e300,"sigma_a":0,"intensity":1e308,"normal":[0,0,1],"eye_dir":[0,0.6,0.8],"light_pos":[0.1,0,1],"length":"inf"})" "\n";
    const Bounded r = run_bounded("eval --table " + default_airlight(), input);
    EXPECT_BOUNDED(r);
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 5u) << r.out;
    EXPECT_EQ(lines[0]["exact"], 0.0) << lines[0];
    EXPECT_EQ(lines[0]["table"], 0.0) << lines[0];
    EXPECT_EQ(lines[1]["exact"], 0.0) << lines[1];
    EXPECT_EQ(lines[1]["table"], 0.0) << lines[1];
    EXPECT_TRUE(lines[2]["exact"].is_null());
    EXPECT_TRUE(contains(lines[2].value("note", ""), "null for exact, table: beyond the largest double")) << lines[2];
    EXPECT_TRUE(lines[3]["exact"].is_number()) << lines[3];
    for (const auto &l : lines)
        for (const char *field : {"exact", "table", "approx", "distant"})
            if (l.contains(field) && l[field].is_null() && !(std::string(field) == "table" && l["quantity"] == "near_light")) {
                EXPECT_TRUE(l.contains("note")) << "a silent null: " << l;
            }
    EXPECT_TRUE(lines[4].contains("note")) << lines[4];
}

TEST(HostileExtremes, AirlightTableAtNanometreAndSmallerDistances) {
    std::string input;
    for (double D : {1e-170, 1e-200, 1e-9, 1e160})
        for (double gamma : {0.13, 0.69, 2.0, 3.0960635525811138, 3.1415891386690555})
            for (double s_over_D : {0.1, 1.0, 4.0, 1e3, 1e6}) {
                const double sigma_s = D > 1.0 ? 1.0 / D : 20.0; // the review's 20/m; sigma D = 1 at 1e160 m
                input += nlohmann::json({{"quantity", "airlight"}, {"sigma_s", sigma_s}, {"sigma_a", 0.0},
                                         {"intensity", 1.0}, {"distance", D}, {"gamma", gamma},
                                         {"length", s_over_D * D}})
                             .dump() +
                         "\n";
            }
    const Bounded r = run_bounded("eval --table " + default_airlight(), input);
    EXPECT_BOUNDED(r);
    for (const auto &l : lines_of(r.out)) {
        ASSERT_TRUE(l["exact"].is_number() && l["table"].is_number()) << l;
        const double exact = l["exact"].get<double>(), table = l["table"].get<double>();
        EXPECT_LE(std::fabs(table - exact), 1e-3 * exact) << l;
    }
}

// ------------------------------------------------------------------ 13: F at small v

TEST(HostileExtremes, TableFKeepsTheDeclaredAccuracyForEveryV) {
    const Bounded info = run_bounded("inspect --json " + default_airlight());
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const double declared = nlohmann::json::parse(info.out)["accuracy"]["sampling_max_rel"].get<double>();
    ASSERT_GT(declared, 0.0);
    std::string input;
    for (double u : {0.0, 1e-6, 0.5, 1.0, 2.0, 5.0, 30.0, 200.0})
        for (double v : {1e-300, 1e-124, 1e-10, 1e-5, 1e-3, 0.01, 0.03, 0.1, 0.3, 0.7, 1.0, 1.4, 1.57})
            input += nlohmann::json({{"quantity", "F"}, {"u", u}, {"v", v}}).dump() + "\n";
    const Bounded r = run_bounded("eval --table " + default_airlight(), input);
    EXPECT_BOUNDED(r);
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 8u * 13u);
    for (const auto &l : lines) {
        ASSERT_TRUE(l["exact"].is_number() && l["table"].is_number()) << l;
        const double exact = l["exact"].get<double>(), table = l["table"].get<double>();
        ASSERT_GT(exact, 0.0) << l;
        EXPECT_LE(std::fabs(table - exact) / exact, declared) << l;
    }
}

// ------------------------------------------------------------------ 11, 12: table files

// A table whose stored logarithms are absurd but finite, with consistent checksums: the
// runtime refuses it at load, naming the node (exit 2), instead of answering null.
TEST(HostileTables, AbsurdButConsistentValuesAreRefusedNamingTheNode) {
    const std::string dir = tmp_dir("absurd");
    scatterlut::Table t = scatterlut::load_table(default_airlight());
    const size_t n_u = static_cast<size_t>(t.axes[0].map.count);
    t.values[3 * n_u + 7] = 3e38; // node (7, 3)
    const std::string path = dir + "/absurd.slut";
    scatterlut::save_binary(t, path);
    for (const std::string &cmd : {"validate " + path, "eval --table " + path}) {
        const Bounded r = run_bounded(cmd, "{\"quantity\":\"F\",\"u\":1,\"v\":0.5}\n");
        EXPECT_BOUNDED(r);
        EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
        EXPECT_TRUE(contains(r.err, "ln G~ = ") && contains(r.err, "at node (7, 3), channel 'ln_Gs' is outside the quantity's range"))
            << r.err;
    }
    t.values[3 * n_u + 7] = 1e-2; // ln G~ > 0: G~ > 1, still refused
    scatterlut::save_binary(t, path);
    EXPECT_EQ(run_bounded("validate " + path).exit_code, 2);
}

TEST(HostileTables, PayloadChecksumMismatchExits1) {
    const std::string dir = tmp_dir("checksum");
    auto bytes = read_bytes(default_airlight());
    bytes[bytes.size() - 5] ^= 0x10;
    const std::string path = dir + "/flipped.slut";
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char *>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    const Bounded v = run_bounded("validate " + path);
    EXPECT_EQ(v.exit_code, 1) << v.out << v.err;
    EXPECT_TRUE(contains(v.out, path + ": FAIL")) << v.out;
    EXPECT_TRUE(contains(v.err, path + ": payload checksum mismatch")) << v.err;
    EXPECT_EQ(run_bounded("inspect " + path).exit_code, 1);
    EXPECT_EQ(run_bounded("eval --table " + path).exit_code, 1);
}
