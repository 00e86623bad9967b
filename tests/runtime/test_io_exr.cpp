// Tests of the EXR table files (docs/FORMAT.md §4): round trips, the channel mapping, the
// header's attributes and checksum, older and newer versions, and hostile inputs. Part of the
// test_io executable (io_test_support.hpp).

#include "io_test_support.hpp"

#ifdef SCATTERLUT_HAS_OPENEXR

namespace {

void expect_exr_error(const Bytes &b, const std::string &needle) {
    expect_load_error([&] { decode_exr(b.data(), b.size(), "test.exr"); }, needle);
}

} // namespace

TEST(Exr, RoundTripAllDimensionsF16F32) {
    ASSERT_TRUE(have_openexr());
    for (size_t dims = 1; dims <= 4; ++dims) {
        for (Storage s : {Storage::F16, Storage::F32}) {
            SCOPED_TRACE(std::to_string(dims) + "-D " + to_string(s));
            const Table t = make_table(dims, s);
            const Bytes b = encode_exr(t);
            const Table back = decode_exr(b.data(), b.size(), "mem.exr");
            expect_same_metadata(t, back);
            expect_values_rounded(t, back);
            EXPECT_EQ(encode_exr(t), b);    // deterministic
            EXPECT_EQ(encode_exr(back), b); // and stable under a round trip
            // Same stored numbers as the binary format.
            const Bytes bin = encode_binary(t);
            const Table from_bin = decode_binary(bin.data(), bin.size(), "mem.slut");
            EXPECT_EQ(from_bin.values, back.values);
        }
    }
}

TEST(Exr, FilesAndDispatchByMagic) {
    TempDir dir;
    const Table t = make_table(3, Storage::F16);
    save_exr(t, dir.path + "/t.exr");
    save_binary(t, dir.path + "/t.slut");
    const Table a = load_table(dir.path + "/t.exr");
    const Table b = load_table(dir.path + "/t.slut");
    EXPECT_EQ(a.values, b.values);
    expect_same_metadata(a, b);
    expect_same_metadata(t, load_exr(dir.path + "/t.exr"));
    expect_load_error([&] { load_binary(dir.path + "/t.exr"); }, "an OpenEXR file: read it with load_table");
    expect_load_error([&] { load_exr(dir.path + "/t.slut"); }, "not an OpenEXR file");
    EXPECT_EQ(dir.entries().size(), 2u);
}

TEST(Exr, F64IsRefusedWithAHint) {
    try {
        encode_exr(make_table(2, Storage::F64));
        ADD_FAILURE();
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("use the binary format"), std::string::npos) << e.what();
    }
}

// Table channels F, ln_G are the EXR channels R, G (mapping version 2, docs/FORMAT.md §4).
TEST(ExrHostile, MissingChannel) {
    Bytes b = encode_exr(make_table(2, Storage::F16));
    const size_t type_at = chlist_type_offset(b, "G");
    b[type_at - 2] = 'X'; // rename "G" → "X" in the channel list only
    expect_exr_error(b, "missing channel 'ln_G' (expected HALF pixels for storage f16) in EXR channel 'G'");
}

TEST(ExrHostile, WrongPixelType) {
    Bytes b = encode_exr(make_table(2, Storage::F16));
    put_u32(&b[chlist_type_offset(b, "R")], 2); // FLOAT
    expect_exr_error(b, "channel 'F' has pixel type FLOAT, expected HALF (storage f16) in EXR channel 'R'");
    b = encode_exr(make_table(1, Storage::F32));
    put_u32(&b[chlist_type_offset(b, "G")], 0); // UINT
    expect_exr_error(b, "channel 'ln_G' has pixel type UINT, expected FLOAT");
}

TEST(ExrHostile, EditedAttributesAndVersions) {
    const Bytes good = encode_exr(make_table(2, Storage::F32));
    Bytes b = good;
    b[find_bytes(b, "scatterlut 0.1.0 (test)")] = 'X'; // generator_version edited
    expect_exr_error(b, "header checksum mismatch");
    b = good;
    const size_t major_at = find_bytes(b, std::string("scatterlut.format_major\0int\0", 28)) + 28 + 4;
    put_u32(&b[major_at], kExrFormatMajor + 1);
    expect_exr_error(b, "test.exr: format version " + std::to_string(kExrFormatMajor + 1) + "." +
                            std::to_string(kExrFormatMinor) + " is newer than this reader (" +
                            std::to_string(kExrFormatMajor) + ".x); upgrade scatterlut");
    put_u32(&b[major_at], 0);
    expect_exr_error(b, "test.exr: format version 0." + std::to_string(kExrFormatMinor) + " is not supported");
    b = good;
    const size_t count_at = find_bytes(b, std::string("scatterlut.axis.1.count\0int\0", 28)) + 28 + 4;
    put_u32(&b[count_at], 7);
    expect_exr_error(b, "header checksum mismatch");
}

TEST(ExrHostile, TruncatedAndCorruptNeverCrash) {
    const Bytes good = encode_exr(make_table(2, Storage::F16));
    for (size_t n = 0; n < good.size(); n += (n < 64 ? 1 : 7)) {
        const Bytes prefix(good.begin(), good.begin() + static_cast<long>(n));
        EXPECT_THROW(decode_exr(prefix.data(), prefix.size(), "cut.exr"), LoadError) << n;
    }
    std::mt19937 rng(99);
    for (int i = 0; i < 500; ++i) {
        Bytes b = good;
        b[rng() % b.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
        try {
            decode_exr(b.data(), b.size(), "flip.exr");
        } catch (const LoadError &) {
        }
    }
}

// The header checksum as docs/FORMAT.md §4.1 defines it, recomputed from the file's bytes
// (attribute list: name\0 type\0 i32 size value …, \0) and written into
// scatterlut.checksum.header, so that an edited header is judged by the reader's checks
// rather than by the checksum.
void refresh_exr_header_checksum(Bytes &b) {
    struct Attr {
        std::string name, type;
        size_t value_at, size;
    };
    std::vector<Attr> attrs;
    size_t pos = 8;
    while (b[pos] != 0) {
        Attr a;
        a.name = reinterpret_cast<const char *>(&b[pos]);
        pos += a.name.size() + 1;
        a.type = reinterpret_cast<const char *>(&b[pos]);
        pos += a.type.size() + 1;
        a.size = get_u32(&b[pos]);
        a.value_at = pos + 4;
        pos = a.value_at + a.size;
        attrs.push_back(a);
    }
    std::sort(attrs.begin(), attrs.end(), [](const Attr &x, const Attr &y) { return x.name < y.name; });
    uint64_t h = 0xcbf29ce484222325ull;
    size_t checksum_at = 0;
    for (const Attr &a : attrs) {
        if (a.name == "scatterlut.checksum.header") checksum_at = a.value_at;
        if (a.name.rfind("scatterlut.", 0) != 0 || a.name.rfind("scatterlut.checksum.", 0) == 0) continue;
        const Bytes size = le_u32(static_cast<uint32_t>(a.size));
        h = doc_fnv1a64(reinterpret_cast<const uint8_t *>(a.name.c_str()), a.name.size() + 1, h);
        h = doc_fnv1a64(reinterpret_cast<const uint8_t *>(a.type.c_str()), a.type.size() + 1, h);
        h = doc_fnv1a64(size.data(), 4, h);
        h = doc_fnv1a64(&b[a.value_at], a.size, h);
    }
    char hex[19];
    std::snprintf(hex, sizeof hex, "0x%016llx", static_cast<unsigned long long>(h));
    std::memcpy(&b[checksum_at], hex, 18);
}

// docs/FORMAT.md §2.7 for EXR: a file of a newer minor version with a scatterlut.*
// attribute this reader does not know is read (the attribute skipped); the same attribute
// in a file of this reader's own version is refused. The unknown attribute replaces
// screenWindowWidth (same name length, type float), so no byte moves.
TEST(Exr, NewerMinorWithUnknownAttributesIsRead) {
    const Table t = make_table(2, Storage::F32);
    const Bytes good = encode_exr(t);
    Bytes b = good;
    const size_t at = find_bytes(b, std::string("screenWindowWidth\0float\0", 24));
    std::memcpy(&b[at], "scatterlut.zz_new", 17);
    const std::string minor_attr("scatterlut.format_minor\0int\0", 28);
    put_u32(&b[find_bytes(b, minor_attr) + minor_attr.size() + 4], kExrFormatMinor + 1);
    refresh_exr_header_checksum(b);
    const Table back = decode_exr(b.data(), b.size(), "newer.exr");
    expect_same_metadata(t, back);
    expect_values_rounded(t, back);

    put_u32(&b[find_bytes(b, minor_attr) + minor_attr.size() + 4], kExrFormatMinor);
    refresh_exr_header_checksum(b);
    expect_exr_error(b, "unknown attribute 'scatterlut.zz_new' (format version " + std::to_string(kExrFormatMajor) +
                            "." + std::to_string(kExrFormatMinor) + " defines no such attribute)");
    // And the helper is faithful: refreshing an unedited file changes nothing.
    Bytes same = good;
    refresh_exr_header_checksum(same);
    EXPECT_EQ(same, good);
}

// The attributes of an EXR header as the file lays them out: name → (type, value bytes).
std::map<std::string, std::pair<std::string, Bytes>> exr_attributes(const Bytes &b) {
    std::map<std::string, std::pair<std::string, Bytes>> out;
    size_t pos = 8;
    while (b[pos] != 0) {
        const std::string name = reinterpret_cast<const char *>(&b[pos]);
        pos += name.size() + 1;
        const std::string type = reinterpret_cast<const char *>(&b[pos]);
        pos += type.size() + 1;
        const size_t size = get_u32(&b[pos]);
        pos += 4;
        out[name] = {type, Bytes(b.begin() + static_cast<long>(pos), b.begin() + static_cast<long>(pos + size))};
        pos += size;
    }
    return out;
}

// Mapping version 2 is what engine loaders open: one table channel is the EXR channel Y,
// two to four are R, G, B, A in table order; no attribute is a `double` (three.js's
// EXRLoader skips them): the reals are decimal strings that read back exactly.
TEST(Exr, EngineChannelNamesAndRealsAsText) {
    Table one = make_table(2, Storage::F32);
    one.channels.resize(1);
    one.values.clear();
    for (size_t n = 0; n < one.node_count(); ++n) one.values.push_back(0.25 + 1e-3 * static_cast<double>(n));
    one.axes[0].map.scale = 0.1; // no short binary fraction: the text must carry all 17 digits
    for (const Table &t : {one, make_table(2, Storage::F16)}) {
        const Bytes b = encode_exr(t);
        const auto attrs = exr_attributes(b);
        std::vector<std::string> channels;
        const Bytes &chlist = attrs.at("channels").second;
        for (size_t p = 0; chlist[p] != 0;) {
            channels.emplace_back(reinterpret_cast<const char *>(&chlist[p]));
            p += channels.back().size() + 1 + 16;
        }
        const std::vector<std::string> want =
            t.channels.size() == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"G", "R"}; // EXR sorts
        EXPECT_EQ(channels, want);
        for (size_t c = 0; c < t.channels.size(); ++c) {
            const auto &a = attrs.at("scatterlut.channel." + std::to_string(c) + ".exr_channel");
            EXPECT_EQ(a.first, "string");
            EXPECT_EQ(std::string(a.second.begin(), a.second.end()), exr_channel_name(t.channels.size(), c, ""));
        }
        for (const auto &kv : attrs) EXPECT_NE(kv.second.first, "double") << kv.first;
        const auto &scale = attrs.at("scatterlut.axis.0.scale");
        EXPECT_EQ(scale.first, "string");
        double v = 0;
        ASSERT_TRUE(detail::parse_decimal_text(std::string(scale.second.begin(), scale.second.end()), &v));
        EXPECT_EQ(v, t.axes[0].map.scale);
        EXPECT_EQ(get_u32(&attrs.at("scatterlut.format_major").second[0]), kExrFormatMajor);
        const Table back = decode_exr(b.data(), b.size(), "mem.exr");
        expect_same_metadata(t, back);
        expect_values_rounded(t, back);
    }
    EXPECT_EQ(exr_channel_name(5, 4, "ln_X"), "ln_X"); // beyond RGBA: the table's own names
}

TEST(Exr, DecimalTextReadsBackExactly) {
    for (double x : {0.0, -0.0, 0.1, 1.0 / 3.0, 1e-300, 4.9e-324, 1.7976931348623157e308, -2.5, SLUT_PIO2_HI}) {
        double y = 1;
        ASSERT_TRUE(detail::parse_decimal_text(detail::decimal_text(x), &y)) << detail::decimal_text(x);
        EXPECT_EQ(std::memcmp(&x, &y, sizeof x), 0) << detail::decimal_text(x);
    }
    EXPECT_EQ(detail::decimal_text(0.5), "0.5");
    EXPECT_EQ(detail::decimal_text(1e-5), "1e-05");
    double y;
    for (const char *bad : {"", " 1", "1 ", "1,5", "0x1p3", "+1", "1e", "--1"})
        EXPECT_FALSE(detail::parse_decimal_text(bad, &y)) << bad;
}

// A version-2 file whose channel mapping or real-number text is edited (checksum made
// consistent) is refused with the attribute named.
TEST(ExrHostile, EditedChannelMappingAndRealText) {
    const Bytes good = encode_exr(make_table(2, Storage::F16));
    Bytes b = good;
    const std::string exr_attr("scatterlut.channel.1.exr_channel\0string\0", 40);
    b[find_bytes(b, exr_attr) + exr_attr.size() + 4] = 'B';
    refresh_exr_header_checksum(b);
    expect_exr_error(b, "channel 1 ('ln_G'): attribute 'scatterlut.channel.1.exr_channel' = 'B', expected 'G'");
    b = good;
    const std::string min_attr("scatterlut.axis.0.min\0string\0", 29);
    b[find_bytes(b, min_attr) + min_attr.size() + 4] = 'x'; // "0" → "x"
    refresh_exr_header_checksum(b);
    expect_exr_error(b, "attribute 'scatterlut.axis.0.min' = 'x' is not a decimal number");
}

// Files written by the version-1.1 mapping (channels named after the table's channels,
// `double` attributes; tests/data/exr-format-1.1, written by scatterlut before 2.0 from
// make_table) are still read, with the same metadata and values.
TEST(Exr, ReadsVersion11Files) {
    const std::string dir = std::string(SLUT_SOURCE_DIR) + "/tests/data/exr-format-1.1/";
    for (size_t dims : {2, 4}) {
        const Storage s = dims == 2 ? Storage::F16 : Storage::F32;
        SCOPED_TRACE(std::to_string(dims) + "-D " + to_string(s));
        const Table t = make_table(dims, s);
        const Bytes old = read_all(dir + "make_table_" + std::to_string(dims) + "d_" + to_string(s) + ".exr");
        const auto attrs = exr_attributes(old);
        ASSERT_EQ(get_u32(&attrs.at("scatterlut.format_major").second[0]), 1u);
        ASSERT_EQ(attrs.at("scatterlut.axis.0.min").first, "double");
        const Table back = decode_exr(old.data(), old.size(), "old.exr");
        expect_same_metadata(t, back);
        expect_values_rounded(t, back);
        EXPECT_EQ(back.values, decode_exr(encode_exr(back).data(), encode_exr(back).size(), "new.exr").values);
    }
    // Version-1 messages name the table channel only, as before.
    Bytes b = read_all(dir + "make_table_2d_f16.exr");
    b[chlist_type_offset(b, "ln_G") - 2] = 'X';
    expect_exr_error(b, "missing channel 'ln_G' (expected HALF pixels for storage f16)");
    b = read_all(dir + "make_table_2d_f16.exr");
    put_u32(&b[chlist_type_offset(b, "F")], 2);
    expect_exr_error(b, "channel 'F' has pixel type FLOAT, expected HALF (storage f16)");
    // An unknown scatterlut.* attribute in a 1.1 file is still corruption (1.1 is the
    // newest version-1 mapping), as in NewerMinorWithUnknownAttributesIsRead.
    const size_t at = find_bytes(b, std::string("screenWindowWidth\0float\0", 24));
    b = read_all(dir + "make_table_2d_f16.exr");
    std::memcpy(&b[at], "scatterlut.zz_new", 17);
    refresh_exr_header_checksum(b);
    expect_exr_error(b, "unknown attribute 'scatterlut.zz_new' (format version 1.1 defines no such attribute)");
}

// Attribute sizes that disagree with the value's own structure. OpenEXR reads a value by
// its type (an int is 4 bytes, a chlist runs to its empty name) and never compares with
// the declared size, so such a file would put it out of step with the pre-scan; each is
// refused before OpenEXR reads the header (docs/FORMAT.md §4.2, docs/FUZZING.md).
TEST(ExrHostile, SizeDisagreeingWithTheValueIsRefused) {
    const Bytes good = encode_exr(make_table(2, Storage::F16));
    Bytes b = good;
    const std::string axes_attr("scatterlut.axes\0int\0", 20);
    put_u32(&b[find_bytes(b, axes_attr) + axes_attr.size()], 5);
    expect_exr_error(b, "attribute 'scatterlut.axes' of type int declares 5 bytes, but a value of type int is 4 bytes");
    b = good;
    const size_t chlist_size_at = find_bytes(b, std::string("channels\0chlist\0", 16)) + 16;
    put_u32(&b[chlist_size_at], get_u32(&b[chlist_size_at]) + 40);
    expect_exr_error(b, "attribute 'channels' of type chlist declares");
    expect_exr_error(b, "but its channel list ends after");
    b = good;
    const std::string extra_attr("scatterlut.extra\0stringvector\0", 30);
    const size_t extra_at = find_bytes(b, extra_attr) + extra_attr.size();
    put_u32(&b[extra_at + 4], 0x7fffffff); // the first string's length
    expect_exr_error(b, "attribute 'scatterlut.extra' of type stringvector declares");
    expect_exr_error(b, "a string at value byte 0 claims 2147483647 bytes");
}

// The fuzzer's finding tests/fuzz/known/exr-oom-1 (3041 bytes): its chlist claims 2327
// bytes and holds 23; OpenEXR 3.1 read on into the declared value and met a "string"
// whose size field was four bytes of text, 2.0 GB, and allocated it before failing.
// Decoded here in a child process whose address space is capped at its current size
// + 256 MiB: such an allocation fails there (std::bad_alloc, a different outcome), so
// this test fails if any allocation sized by an unchecked field comes back.
TEST(ExrHostile, FuzzFindingExrOomRefusedWithBoundedMemory) {
    const Bytes file = read_all(std::string(SLUT_SOURCE_DIR) + "/tests/fuzz/known/exr-oom-1");
    ASSERT_EQ(file.size(), 3041u);
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::close(fds[0]);
        auto report = [&](int code, const std::string &what) {
            if (::write(fds[1], what.data(), what.size()) < 0) code = 9;
            ::_exit(code);
        };
        std::ifstream status("/proc/self/status");
        std::string line;
        unsigned long long vm_kib = 0;
        while (std::getline(status, line))
            if (line.rfind("VmSize:", 0) == 0) vm_kib = std::strtoull(line.c_str() + 7, nullptr, 10);
        if (vm_kib == 0) report(5, "no VmSize in /proc/self/status");
        struct rlimit cap;
        cap.rlim_cur = cap.rlim_max = (vm_kib << 10) + (256ull << 20);
        if (::setrlimit(RLIMIT_AS, &cap) != 0) report(6, "setrlimit failed");
        try {
            decode_exr(file.data(), file.size(), "exr-oom-1");
            report(2, "decoded without error");
        } catch (const LoadError &e) {
            report(0, e.what());
        } catch (const std::bad_alloc &) {
            report(3, "std::bad_alloc: an allocation beyond the 256 MiB cap");
        } catch (const std::exception &e) {
            report(4, std::string("not a LoadError: ") + e.what());
        }
    }
    ::close(fds[1]);
    std::string message;
    char buf[512];
    ssize_t n;
    while ((n = ::read(fds[0], buf, sizeof buf)) > 0) message.append(buf, static_cast<size_t>(n));
    ::close(fds[0]);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "child died: signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 0) << message;
    EXPECT_NE(message.find("exr-oom-1: EXR header: attribute 'channels' of type chlist declares 2327 bytes, but its "
                           "channel list ends after 23"),
              std::string::npos)
        << message;
}

#else

TEST(Exr, BuiltWithoutOpenExr) {
    EXPECT_FALSE(have_openexr());
    const Bytes b = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
    expect_load_error([&] { decode_exr(b.data(), b.size(), "x.exr"); }, "built without OpenEXR");
    EXPECT_THROW(encode_exr(make_table(1, Storage::F32)), std::runtime_error);
}

#endif
