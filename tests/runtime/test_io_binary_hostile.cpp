// Tests of the binary table files (docs/FORMAT.md §2) against hostile inputs: truncation, wrong
// magic, flipped bytes, huge or negative counts, non-finite payloads, bad fields, structural
// corruption, unknown versions, fuzzed headers. Part of the test_io executable
// (io_test_support.hpp: the documented layout, re-implemented).

#include "io_test_support.hpp"

TEST(BinaryHostile, TruncatedAtEveryPrefixLength) {
    for (Storage s : {Storage::F16, Storage::F64}) {
        const Bytes b = encode_binary(make_table(2, s));
        for (size_t n = 0; n < b.size(); ++n) {
            const Bytes prefix(b.begin(), b.begin() + static_cast<long>(n));
            expect_decode_error(prefix, "truncated");
            if (HasFailure()) {
                ADD_FAILURE() << "at prefix length " << n;
                return;
            }
        }
    }
}

TEST(BinaryHostile, WrongMagic) {
    Bytes b = encode_binary(make_table(1, Storage::F32));
    b[3] = 'X';
    expect_decode_error(b, "not a scatterlut binary table: expected magic 53 4c 55 54 54 42 4c 00");
    const Bytes exr = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0, 0, 0};
    expect_decode_error(exr, "an OpenEXR file");
}

TEST(BinaryHostile, ChecksumsCatchFlippedBytes) {
    const Bytes good = encode_binary(make_table(2, Storage::F32));
    Bytes b = good;
    b[b.size() - 5] ^= 0x10; // payload
    expect_decode_error(b, "payload checksum mismatch");
    b = good;
    b[60] ^= 0x01; // inside the header section
    expect_decode_error(b, "header checksum mismatch");
    b = good;
    b[40] ^= 0x01; // the stored payload checksum itself
    expect_decode_error(b, "payload checksum mismatch");
}

TEST(BinaryHostile, HugeNodeCountRefusedBeforeAllocation) {
    File f = parse(encode_binary(make_table(2, Storage::F32)));
    set_nested(f, kAxisTag, 0, 7, le_u32(1000000));
    set_nested(f, kAxisTag, 1, 7, le_u32(1000000)); // 10^12 nodes; payload unchanged
    expect_decode_error(build(f), "header claims 1000000000000 nodes, more than the limit of 2^31");
}

TEST(BinaryHostile, NegativeZeroAndOneCounts) {
    for (int32_t count : {-1, 0, 1, std::numeric_limits<int32_t>::min()}) {
        File f = parse(encode_binary(make_table(2, Storage::F32)));
        set_nested(f, kAxisTag, 1, 7, le_u32(static_cast<uint32_t>(count)));
        expect_decode_error(build(f), "axis 1 ('w'): count " + std::to_string(count) + " is invalid");
    }
}

TEST(BinaryHostile, NonFinitePayloadWithValidChecksum) {
    for (uint32_t bits : {0x7fc00000u, 0x7f800000u, 0xff800000u}) {
        File f = parse(encode_binary(make_table(2, Storage::F32)));
        put_u32(&f.payload[4 * 13], bits); // node (6, 0), channel 1
        expect_decode_error(build(f), "payload value at node (6, 0), channel 'ln_G' is not finite");
    }
    File f = parse(encode_binary(make_table(1, Storage::F16)));
    f.payload[0] = 0x00;
    f.payload[1] = 0x7e; // f16 NaN
    expect_decode_error(build(f), "is not finite (nan)");
}

TEST(BinaryHostile, BadAxisAndEnumerationFields) {
    const File good = parse(encode_binary(make_table(2, Storage::F32)));
    File f = good;
    set_nested(f, kAxisTag, 0, 3, le_f64(NAN));
    expect_decode_error(build(f), "axis 0 ('u'): range [nan, 50] / scale 0.5 is not finite");
    f = good;
    set_nested(f, kAxisTag, 0, 4, le_f64(INFINITY));
    expect_decode_error(build(f), "is not finite");
    f = good;
    set_nested(f, kAxisTag, 0, 3, le_f64(50.0)); // min = max
    expect_decode_error(build(f), "axis 0 ('u'): min 50 must be less than max 50");
    f = good;
    set_nested(f, kAxisTag, 1, 6, le_u32(9));
    expect_decode_error(build(f), "axis 1 ('w'): unknown warp id 9");
    f = good;
    set_nested(f, kChannelTag, 1, 3, le_u32(7));
    expect_decode_error(build(f), "channel 1 ('ln_G'): unknown encoding id 7");
    f = good;
    nth(f.header, 0x03).value = le_u32(4);
    expect_decode_error(build(f), "unknown storage id 4");
    f = good;
    nth(f.header, 0x03).value = le_u32(3); // claims f64, payload holds f32
    expect_decode_error(build(f), "payload is 280 bytes, expected 560");
    f = good;
    set_nested(f, kAxisTag, 1, 3, le_f64(-0.5)); // asinh_cot below 0: check_consistent
    expect_decode_error(build(f), "inconsistent table: axis 1 ('w'): warp 'asinh_cot' needs min > 0");
}

TEST(BinaryHostile, StructuralCorruption) {
    const Bytes good_bytes = encode_binary(make_table(2, Storage::F32));
    const File good = parse(good_bytes);
    File f = good;
    f.header.push_back(f.header[0]); // a second 'kind'
    expect_decode_error(build(f), "field 'kind' appears twice");
    f = good;
    f.header.erase(f.header.begin());
    expect_decode_error(build(f), "required field 'kind' is missing");
    f = good;
    {
        std::vector<Rec> inner = split(nth(f.header, kAxisTag).value);
        inner.pop_back(); // drop 'count'
        nth(f.header, kAxisTag).value = join(inner);
    }
    expect_decode_error(build(f), "axis 0: required field 'count' is missing");
    f = good;
    nth(f.header, 0x02).value = Bytes(3, 0); // quantity_version must be 4 bytes
    expect_decode_error(build(f), "field 'quantity_version' is 3 bytes, expected 4");
    f = good;
    nth(f.header, 0x01).value = Bytes(300, 'k');
    expect_decode_error(build(f), "field 'kind' is 300 bytes, more than the limit 256");
    f = good;
    for (int i = 0; i < 9; ++i) f.header.push_back(nth(f.header, kAxisTag));
    expect_decode_error(build(f), "more than 8 axes");

    // A record whose length runs past the header (checksum recomputed over the lie).
    Bytes b = good_bytes;
    put_u32(&b[48 + 4], 0x7fffffff);
    put_u64(&b[32], doc_fnv1a64(&b[48], get_u64(&b[16]), doc_fnv1a64(b.data(), 32)));
    expect_decode_error(b, "claims 2147483647 bytes but only");

    b = good_bytes;
    put_u64(&b[16], uint64_t{1} << 40);
    expect_decode_error(b, "header size 1099511627776 exceeds the limit");
    b = good_bytes;
    put_u64(&b[24], ~uint64_t{0});
    expect_decode_error(b, "truncated");
    b = good_bytes;
    b.push_back(0);
    expect_decode_error(b, "1 unexpected bytes after the payload");
}

TEST(BinaryHostile, UnknownMajorVersionRefused) {
    Bytes b = encode_binary(make_table(1, Storage::F32));
    put_u32(&b[8], 2);
    put_u32(&b[12], 0);
    expect_decode_error(b, "test.slut: format version 2.0 is newer than this reader (1.x); upgrade scatterlut");
    put_u32(&b[8], 0);
    expect_decode_error(b, "format version 0.0 is older");
}

TEST(BinaryHostile, NewerMinorWithUnknownFieldsIsRead) {
    const Table t = make_table(2, Storage::F32);
    File f = parse(encode_binary(t));
    f.minor = kFormatMinor + 1;
    f.header.push_back(Rec{0x7001, Bytes{1, 2, 3, 4, 5}});                       // top level
    nth(f.header, kAxisTag, 1).value = join([&] {                               // nested, in an axis
        std::vector<Rec> inner = split(nth(f.header, kAxisTag, 1).value);
        inner.push_back(Rec{42, le_f64(1.5)});
        return inner;
    }());
    nth(f.header, kProvenanceTag).value.insert(nth(f.header, kProvenanceTag).value.end(), {99, 0, 0, 0, 1, 0, 0, 0, 7});
    const Bytes b = build(f);
    const Table back = decode_binary(b.data(), b.size(), "newer.slut");
    expect_same_metadata(t, back);
    expect_values_rounded(t, back);

    // The same unknown field in a file of this reader's own version is corruption.
    f.minor = kFormatMinor;
    expect_decode_error(build(f), "unknown field tag");
}

// Random mutations of the header with checksums repaired, so that the record parser
// (not the checksum) meets them: every outcome is a table or a LoadError.
TEST(BinaryHostile, FuzzedHeadersNeverCrash) {
    const Bytes good = encode_binary(make_table(3, Storage::F16));
    const uint64_t hs = get_u64(&good[16]);
    std::mt19937 rng(12345);
    int refused = 0;
    for (int iter = 0; iter < 4000; ++iter) {
        Bytes b = good;
        const int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            const size_t at = 48 + rng() % hs;
            switch (rng() % 3) {
            case 0: b[at] ^= static_cast<uint8_t>(1u << (rng() % 8)); break;
            case 1: b[at] = static_cast<uint8_t>(rng()); break;
            default: b[at] = (rng() % 2) ? 0xff : 0x00; break;
            }
        }
        put_u64(&b[32], doc_fnv1a64(&b[48], hs, doc_fnv1a64(b.data(), 32)));
        try {
            decode_binary(b.data(), b.size(), "fuzz");
        } catch (const LoadError &) {
            ++refused;
        }
    }
    EXPECT_GT(refused, 1000);
}
