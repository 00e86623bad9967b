#include "simd4.hpp"

#if SLUT_HAVE_SIMD4
namespace scatterlut::simd4 {

bool cpu_has_avx2_fma() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

} // namespace scatterlut::simd4
#endif
