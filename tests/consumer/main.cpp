// Links scatterlut::tables from an installed prefix: loads a table, samples radiance,
// compares with the exact quadrature. Exit 0 when they agree to 0.1 %.
#include <cmath>
#include <cstdio>

#include <scatterlut/airlight.hpp>
#include <scatterlut/io.hpp>

int main(int argc, char **argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: consumer airlight_F.slut\n");
        return 2;
    }
    const scatterlut::AirlightTable fog(scatterlut::load_table(argv[1]));
    const scatterlut::AirlightQuery q{0.05, 0.01, 100.0, 10.0, 0.3, 20.0};
    const double table = fog.radiance(q), exact = scatterlut::airlight_radiance_exact(q);
    std::printf("table %.9g exact %.9g\n", table, exact);
    return std::fabs(table - exact) <= 1e-3 * exact ? 0 : 1;
}
