// scatterlut runtime — reading and writing table files (layout: docs/FORMAT.md).
//
// Two formats hold the same Table:
//   binary  little-endian, checksummed, no dependency but this library; f16/f32/f64;
//   EXR     OpenEXR single-part scanline image (slices of 3-D/4-D tables stacked into
//           a vertical atlas), metadata as `scatterlut.*` attributes; f16/f32 only.
// A third, KTX 2.0, is written for engines (GPU textures) but not read back.
// Loaders distrust their input: every length is checked against the bytes present
// before anything is allocated, and every failure is a LoadError naming the file.
// Writers are atomic (temp file in the target directory, fsync, rename) and
// deterministic (the same Table gives byte-identical files).
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "scatterlut/table.hpp"

namespace scatterlut {

// A table file that cannot be used: unreadable, truncated, corrupt, unsupported.
// what() always starts with the file name and says what was expected.
class LoadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A table file whose stored checksum (header or payload) does not match its bytes: a file
// that was read but is corrupt. The scatterlut command exits 1 for it (2 for LoadError).
class ChecksumError : public LoadError {
public:
    using LoadError::LoadError;
};

// Format limits (binary and EXR). Writers refuse tables beyond them with
// std::invalid_argument; readers refuse files beyond them with LoadError.
inline constexpr size_t kMaxChannels = 16;
inline constexpr uint64_t kMaxNodes = uint64_t{1} << 31;          // product of axis counts
inline constexpr uint64_t kMaxHeaderBytes = uint64_t{16} << 20;   // binary header section
inline constexpr size_t kMaxNameBytes = 256;        // kind, axis/channel names, extra keys
inline constexpr size_t kMaxTextBytes = 4096;       // meanings, versions, device, domain
inline constexpr size_t kMaxLongTextBytes = 1 << 20; // command line, extra values
inline constexpr size_t kMaxSceneBytes = 4 << 20;    // scene text
inline constexpr size_t kMaxExtraEntries = 1024;

// --- any format ----------------------------------------------------------------------
// Reads a binary or EXR table, chosen by the file's magic number.
Table load_table(const std::string &path);

// --- binary ----------------------------------------------------------------------------
Table load_binary(const std::string &path);
// Atomic, deterministic. Throws std::invalid_argument for a table the format cannot hold
// (inconsistent, beyond the limits, a value that overflows the storage type) and
// std::system_error if the file cannot be written; the previous file is then untouched.
void save_binary(const Table &table, const std::string &path);
std::vector<uint8_t> encode_binary(const Table &table);
Table decode_binary(const uint8_t *data, size_t size, const std::string &name_for_messages);

// --- OpenEXR ---------------------------------------------------------------------------
// EXR mapping version written by encode_exr (docs/FORMAT.md §4). 2.0 names the value
// channels as engine loaders expect (Y, or R, G, B, A) and stores every real number as a
// decimal string attribute; decode_exr reads 2.x and the older 1.x files (semantic
// channel names, double attributes). The binary format keeps its own version
// (kFormatMajor.kFormatMinor).
inline constexpr uint32_t kExrFormatMajor = 2;
inline constexpr uint32_t kExrFormatMinor = 0;
// The EXR channel that holds table channel `index` of a table with `count` channels in a
// version-2 file: "Y" for a single channel; "R", "G", "B", "A" for 2 to 4 channels (in
// table order); the table channel's own name beyond 4.
std::string exr_channel_name(size_t count, size_t index, const std::string &table_channel_name);
// True if this library was built with OpenEXR; otherwise the functions below throw
// (LoadError for the readers, std::runtime_error for the writers).
bool have_openexr();
Table load_exr(const std::string &path);
// As save_binary; storage f64 is not representable in EXR: std::invalid_argument.
void save_exr(const Table &table, const std::string &path);
std::vector<uint8_t> encode_exr(const Table &table);
Table decode_exr(const uint8_t *data, size_t size, const std::string &name_for_messages);

// --- KTX 2.0 (docs/FORMAT.md §6) ---------------------------------------------------------
// An uncompressed GPU texture: R16_SFLOAT / R32_SFLOAT (R…RGBA for 2 to 4 channels), one
// mip level; a 1-D table is a 1-D texture, 2-D a 2-D texture, 3-D a 3-D texture, 4-D a 3-D
// texture with axis 3 stacked along y (x = i0, y = i1 + c1·i3, z = i2). Metadata in the
// key/value data as text (keys "scatterlut.*", version kKtx2FormatMajor.kKtx2FormatMinor).
// Written only (no reader): std::invalid_argument for f64 storage, more than 4 channels or
// 4 axes. Atomic and deterministic like the other writers.
inline constexpr uint32_t kKtx2FormatMajor = 1;
inline constexpr uint32_t kKtx2FormatMinor = 0;
struct Ktx2Shape {
    uint64_t width = 0, height = 0, depth = 0; // pixelWidth, pixelHeight (0: 1-D), pixelDepth (0: not 3-D)
};
Ktx2Shape ktx2_shape(const Table &table);
void save_ktx2(const Table &table, const std::string &path);
std::vector<uint8_t> encode_ktx2(const Table &table);

// --- storage rounding --------------------------------------------------------------------
// Largest relative error on the quantity (Linear: the stored value; Log: exp(stored))
// caused by rounding table.values to storage s, round-to-nearest-even. 0 for an exact
// rounding (and for a zero quantity stored exactly); +inf if a value overflows s.
// Throws std::invalid_argument if a value is not finite.
double storage_rounding_max_rel(const Table &table, Storage s);

// IEEE 754 binary16 conversions, independent of OpenEXR/Imath. f16_from_double rounds
// to nearest, ties to even, directly from double (no double rounding through float);
// overflow gives ±inf, subnormals are produced and read exactly.
uint16_t f16_from_double(double x);
double double_from_f16(uint16_t h);
// x rounded to storage s, widened back to double (overflow: ±inf).
double round_to_storage(double x, Storage s);

// 64-bit FNV-1a (offset basis 0xcbf29ce484222325, prime 0x100000001b3), continued from
// `state` so that a checksum can be computed over several pieces.
inline constexpr uint64_t kFnv1a64Basis = 0xcbf29ce484222325ull;
uint64_t fnv1a64(const void *data, size_t size, uint64_t state = kFnv1a64Basis);

// Writes bytes to path atomically: a uniquely named temp file in the same directory,
// fsync, rename over path, fsync of the directory. On failure the temp file is removed,
// the previous file is untouched, and std::system_error names the path.
void write_file_atomic(const std::string &path, const std::vector<uint8_t> &bytes);

// Several files made visible together (one run's output set): add() writes each file's
// bytes to its own hidden temporary beside the final name (fsynced, registered for
// remove_temporaries_in_progress), commit() then renames them all in the order added and
// fsyncs their directories. Until commit() no final name changes, so an error or a signal
// before it leaves the previous files whole; destroying an uncommitted set removes its
// temporaries. Throws std::system_error naming the path. Not copyable.
class AtomicFileSet {
public:
    AtomicFileSet();
    ~AtomicFileSet();
    AtomicFileSet(const AtomicFileSet &) = delete;
    AtomicFileSet &operator=(const AtomicFileSet &) = delete;
    void add(const std::string &path, const std::vector<uint8_t> &bytes);
    void commit();

private:
    struct Pending;
    std::vector<Pending> pending_;
};

// Unlinks the temporary files of the write_file_atomic calls in progress in this process,
// leaving every final name as it was. Async-signal-safe (reads lock-free flags, calls
// unlink): meant for a SIGINT/SIGTERM handler, which then re-raises the signal. A SIGKILL
// cannot be handled and leaves the hidden temporary file ('.NAME.tmp-PID-N').
void remove_temporaries_in_progress() noexcept;

namespace detail {
// Shared by the binary and EXR codecs; not a stable API.
std::vector<uint8_t> read_file(const std::string &path); // throws LoadError
// A regular file of at most max_bytes (FIFOs, devices and directories are refused without
// blocking: opened O_NONBLOCK, checked by fstat before any read); `expected` names what
// the file should be in messages ("a table file"). Throws LoadError.
std::vector<uint8_t> read_file(const std::string &path, uint64_t max_bytes, const char *expected);
// Table::check_consistent() plus the format limits above; std::invalid_argument.
void check_limits(const Table &table);
// The payload as stored: values rounded to table.storage, little-endian, in table order.
// Throws std::invalid_argument naming the node if a value overflows the storage type.
std::vector<uint8_t> encode_payload(const Table &table);
// "(i0, i1, …), channel 'name'" for the value at flat index i.
std::string describe_value(const Table &table, size_t i);
// The shortest decimal text that reads back as exactly x ("0.5", "1e-05", "-inf", "nan"),
// locale-independent, for metadata stored as text (EXR 2.x attributes, KTX2 key/values).
std::string decimal_text(double x);
// Parses all of s as a decimal number (as decimal_text writes it; also "inf", "nan").
// False if s is empty or holds anything else.
bool parse_decimal_text(const std::string &s, double *out);
} // namespace detail

} // namespace scatterlut
