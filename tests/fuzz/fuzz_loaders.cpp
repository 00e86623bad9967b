// libFuzzer target for the table loaders: any byte string must either decode into a
// consistent table or raise LoadError — never crash, hang, leak, allocate beyond the
// fuzzer's limits or throw anything else. Built twice (tests/fuzz/run_fuzz.cmake): without
// a define it fuzzes the binary loader, with -DSLUT_FUZZ_EXR the EXR loader (one format
// per binary, so that neither spends its time on inputs only the other can parse).
// docs/FUZZING.md says how to run them longer.
#include <cstddef>
#include <cstdint>

#include "scatterlut/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    try {
#ifdef SLUT_FUZZ_EXR
        const scatterlut::Table t = scatterlut::decode_exr(data, size, "fuzz.exr");
#else
        const scatterlut::Table t = scatterlut::decode_binary(data, size, "fuzz.slut");
#endif
        t.check_consistent(); // a table that loads must be usable
    } catch (const scatterlut::LoadError &) {
    }
    return 0;
}
