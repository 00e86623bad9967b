#include "simd4.hpp"

#if SLUT_HAVE_SIMD4
namespace scatterlut::simd4 {

bool available() {
    static const bool yes = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }();
    return yes;
}

} // namespace scatterlut::simd4
#endif
