// Global adaptive Gauss–Kronrod (G7–K15, QUADPACK's qk15 nodes) over a list of pieces
// (internal; the spot's surface terms, spot_surface.cpp). Each piece [a, b] may be mapped by the smoothstep x = a + (b − a)(3t² − 2t³), t ∈ [0, 1], whose Jacobian
// 6t(1 − t) vanishes at both ends: an integrand that behaves like √(x − a) or (x − a) ln(x − a)
// at a break becomes smooth in t (the nested integrals of the spot's surface terms have such
// ends where a great circle grazes the cone or the ray runs through the apex).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace scatterlut::gk15 {

constexpr double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Panel {
    int piece;          // index into the pieces
    double t0, t1;      // in the piece's own variable (x, or t of the smoothstep)
    double value, error;
    bool operator<(const Panel &o) const { return error < o.error; }
};

// An interval [a, b] of the integration variable.
struct Piece {
    double a, b;
};

// The integral of f over the union of the pieces (b > a; others skipped), each mapped by the
// smoothstep when `smooth_ends`. Halves the panel of largest |K15 − G7| until the sum of
// those is ≤ rel_tol·|integral| (or ≤ abs_tol), the panel count reaches max_panels or a panel
// can no longer be halved in double. Returns the sum of the panels' K15 values;
// `*error_estimate` (if given) the summed |K15 − G7|.
template <class F>
double integrate(const F &f, const std::vector<Piece> &given, bool smooth_ends, double rel_tol, double abs_tol,
                 int max_panels, double *error_estimate = nullptr) {
    struct Span {
        double a, width;
    };
    std::vector<Span> pieces;
    pieces.reserve(given.size());
    for (const Piece &p : given)
        if (p.b > p.a) pieces.push_back({p.a, p.b - p.a});
    const auto eval = [&](int piece, double t0, double t1) {
        const Span &p = pieces[static_cast<size_t>(piece)];
        const auto g = [&](double t) {
            if (!smooth_ends) return f(p.a + p.width * t);
            const double x = p.a + p.width * (t * t * (3.0 - 2.0 * t));
            const double jac = 6.0 * t * (1.0 - t) * p.width;
            return jac == 0.0 ? 0.0 : f(x) * jac;
        };
        const double c = 0.5 * (t0 + t1), r = 0.5 * (t1 - t0);
        const double fc = g(c);
        double k = kWgk[7] * fc, gs = kWg[3] * fc;
        for (int j = 0; j < 7; ++j) {
            const double sum = g(c - r * kXgk[j]) + g(c + r * kXgk[j]);
            k += kWgk[j] * sum;
            if (j % 2 == 1) gs += kWg[j / 2] * sum;
        }
        const double scale = smooth_ends ? 1.0 : p.width; // t of the smoothstep runs over [0, 1]
        return Panel{piece, t0, t1, k * r * scale, std::fabs((k - gs) * r * scale)};
    };
    std::vector<Panel> heap;
    heap.reserve(static_cast<size_t>(std::max(max_panels, 1)) + 2);
    double total = 0.0, error = 0.0;
    for (size_t i = 0; i < pieces.size(); ++i) {
        const Panel p = eval(static_cast<int>(i), 0.0, 1.0);
        heap.push_back(p);
        total += p.value;
        error += p.error;
    }
    std::make_heap(heap.begin(), heap.end());
    while (!heap.empty() && static_cast<int>(heap.size()) < max_panels && error > rel_tol * std::fabs(total) &&
           error > abs_tol) {
        std::pop_heap(heap.begin(), heap.end());
        const Panel worst = heap.back();
        const double mid = 0.5 * (worst.t0 + worst.t1);
        if (!(mid > worst.t0 && mid < worst.t1)) { // at the resolution of doubles: keep it
            std::push_heap(heap.begin(), heap.end());
            break;
        }
        heap.pop_back();
        const Panel left = eval(worst.piece, worst.t0, mid), right = eval(worst.piece, mid, worst.t1);
        total += left.value + right.value - worst.value;
        error += left.error + right.error - worst.error;
        heap.push_back(left);
        std::push_heap(heap.begin(), heap.end());
        heap.push_back(right);
        std::push_heap(heap.begin(), heap.end());
    }
    total = 0.0; // afresh: no drift from the updates
    error = 0.0;
    for (const Panel &p : heap) {
        total += p.value;
        error += p.error;
    }
    if (error_estimate) *error_estimate = error;
    return total;
}

} // namespace scatterlut::gk15
