// The command line on hostile table files (docs/FORMAT.md §2.6/§4.2): `validate` and `inspect`
// exit 2 with the reason. Part of the test_io executable (io_test_support.hpp).

#include "io_test_support.hpp"

namespace {

struct Corruption {
    const char *name; // file name in the temp dir; the extension picks the format
    Bytes bytes;
    std::string message; // what the reason must say (after the file name)
    int exit_code = 2;   // 1 for a checksum failure: the file was read, and is corrupt
};

std::vector<Corruption> corruptions() {
    std::vector<Corruption> out;
    const Bytes good = encode_binary(make_table(2, Storage::F32));
    out.push_back({"truncated.slut", Bytes(good.begin(), good.begin() + static_cast<long>(good.size() / 2)),
                   "truncated"});
    Bytes b = good;
    b[3] = 'X';
    out.push_back({"magic.slut", b, "not a scatterlut binary table: expected magic 53 4c 55 54 54 42 4c 00"});
    b = good;
    b[b.size() - 5] ^= 0x10;
    out.push_back({"flipped.slut", b, "payload checksum mismatch", 1});
    File f = parse(good);
    set_nested(f, kAxisTag, 0, 7, le_u32(1000000));
    set_nested(f, kAxisTag, 1, 7, le_u32(1000000));
    out.push_back({"huge.slut", build(f), "header claims 1000000000000 nodes, more than the limit of 2^31"});
    f = parse(good);
    set_nested(f, kAxisTag, 1, 7, le_u32(static_cast<uint32_t>(-5)));
    out.push_back({"negative.slut", build(f), "axis 1 ('w'): count -5 is invalid"});
    f = parse(good);
    put_u32(&f.payload[4 * 13], 0x7fc00000u); // NaN, checksum consistent
    out.push_back({"nan.slut", build(f), "payload value at node (6, 0), channel 'ln_G' is not finite (nan)"});
    f = parse(good);
    put_u32(&f.payload[0], 0xff800000u); // −inf
    out.push_back({"inf.slut", build(f), "payload value at node (0, 0), channel 'F' is not finite (-inf)"});
    b = good;
    put_u32(&b[8], 2);
    out.push_back({"major.slut", b,
                   "format version 2." + std::to_string(kFormatMinor) + " is newer than this reader (1.x); upgrade scatterlut"});
#ifdef SCATTERLUT_HAS_OPENEXR
    const Bytes exr = encode_exr(make_table(2, Storage::F16));
    b = exr;
    b[chlist_type_offset(b, "G") - 2] = 'X';
    out.push_back({"nochannel.exr", b, "missing channel 'ln_G' (expected HALF pixels for storage f16) in EXR channel 'G'"});
    b = exr;
    put_u32(&b[chlist_type_offset(b, "R")], 2);
    out.push_back({"type.exr", b, "channel 'F' has pixel type FLOAT, expected HALF (storage f16) in EXR channel 'R'"});
    out.push_back({"exr-oom-1.exr", read_all(std::string(SLUT_SOURCE_DIR) + "/tests/fuzz/known/exr-oom-1"),
                   "EXR header: attribute 'channels' of type chlist declares 2327 bytes"});
#endif
    return out;
}

} // namespace

// Each corruption of docs/FORMAT.md §2.6/§4.2 through the executable: exit 2 from
// `validate` (text and --json) and `inspect` (exit 1 and FAIL for a checksum mismatch: a
// file read but corrupt), the reason on stderr as "scatterlut: FILE:
// reason", and validate's report naming the file UNREADABLE.
TEST(CliHostile, ValidateAndInspectExit2WithTheReason) {
    TempDir dir;
    for (const Corruption &c : corruptions()) {
        SCOPED_TRACE(c.name);
        const std::string path = dir.path + "/" + c.name;
        write_all(path, c.bytes);
        const std::string reason = path + ": " + c.message;
        const char *status = c.exit_code == 1 ? "FAIL" : "UNREADABLE";
        const auto v = slut_test::run_scatterlut("validate " + path);
        EXPECT_EQ(v.exit_code, c.exit_code) << v.out << v.err;
        EXPECT_NE(v.err.find(reason), std::string::npos) << v.err;
        EXPECT_NE(v.out.find(path + ": " + status), std::string::npos) << v.out;
        const auto j = slut_test::run_scatterlut("validate --json " + path);
        EXPECT_EQ(j.exit_code, c.exit_code);
        const nlohmann::json doc = nlohmann::json::parse(j.out);
        EXPECT_EQ(doc.at("status"), status);
        EXPECT_NE(doc.at("message").get<std::string>().find(reason), std::string::npos) << j.out;
        const auto i = slut_test::run_scatterlut("inspect " + path);
        EXPECT_EQ(i.exit_code, c.exit_code) << i.out;
        EXPECT_NE(i.err.find("scatterlut: " + reason), std::string::npos) << i.err;
        EXPECT_TRUE(i.out.empty()) << i.out;
    }
}
