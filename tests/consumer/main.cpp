// Links scatterlut::tables from an installed prefix: loads a table, samples radiance,
// compares with the exact quadrature. Exit 0 when they agree to 0.1 %.
// Where the library has OpenEXR (SCATTERLUT_HAS_OPENEXR, from find_package or pkg-config),
// the same table is also read from its EXR file with load_exr itself, so the consumer links
// the library's OpenEXR code: flags that leave out OpenEXR's libraries fail the link.
#include <cmath>
#include <cstdio>

#include <scatterlut/airlight.hpp>
#include <scatterlut/io.hpp>

namespace {

bool agrees(const char *what, const scatterlut::Table &loaded) {
    const scatterlut::AirlightTable fog(loaded);
    const scatterlut::AirlightQuery q{0.05, 0.01, 100.0, 10.0, 0.3, 20.0};
    const double table = fog.radiance(q), exact = scatterlut::airlight_radiance_exact(q);
    std::printf("%s: table %.9g exact %.9g\n", what, table, exact);
    return std::fabs(table - exact) <= 1e-3 * exact;
}

} // namespace

int main(int argc, char **argv) {
#ifdef SCATTERLUT_HAS_OPENEXR
    if (argc != 3) {
        std::fprintf(stderr, "usage: consumer airlight_F.slut airlight_F.exr\n");
        return 2;
    }
    if (!scatterlut::have_openexr()) {
        std::fprintf(stderr, "SCATTERLUT_HAS_OPENEXR is defined but the library has no OpenEXR\n");
        return 1;
    }
#else
    if (argc != 2) {
        std::fprintf(stderr, "usage: consumer airlight_F.slut\n");
        return 2;
    }
#endif
    bool ok = agrees("binary", scatterlut::load_table(argv[1]));
#ifdef SCATTERLUT_HAS_OPENEXR
    ok = agrees("EXR", scatterlut::load_exr(argv[2])) && ok;
#endif
    return ok ? 0 : 1;
}
