// libFuzzer target for the table loaders: any byte string must either decode into a
// consistent table or raise LoadError — never crash, hang, leak or throw anything else.
// Build and run: see docs/FUZZING.md (CTest runs the binary loader for SLUT_FUZZ_SECONDS,
// default 60). -DSLUT_FUZZ_EXR adds the EXR loader, which has an open finding:
// tests/fuzz/known/exr-oom-1 (3 KB) makes OpenEXR's Header::readFrom allocate ~2 GB
// before our LoadError; docs/FUZZING.md.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "scatterlut/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    try {
        const scatterlut::Table t = scatterlut::decode_binary(data, size, "fuzz.slut");
        t.check_consistent(); // a table that loads must be usable
    } catch (const scatterlut::LoadError &) {
    }
#ifdef SLUT_FUZZ_EXR
    if (scatterlut::have_openexr()) {
        try {
            const scatterlut::Table t = scatterlut::decode_exr(data, size, "fuzz.exr");
            t.check_consistent();
        } catch (const scatterlut::LoadError &) {
        }
    }
#endif
    return 0;
}
