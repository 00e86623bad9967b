#!/usr/bin/env python3
"""The polynomials of the near-light kernel's 2^v and expm1 (kernels/slut_nearlight_lanes.h).

    python3 kernels/exp2_minimax.py            # prints the coefficients as C hex literals
    python3 kernels/exp2_minimax.py --check    # recomputes them, compares with the header

Both write 2^f on [-1/2, 1/2] as 1 + f*P(f) and take P from Remez's exchange algorithm on
the weighted error (P - g) * w, g(f) = (2^f - 1)/f (ln 2 at 0), 60 digits:
  exp2  (slut_nl_lanes_exp2, the sweep's node loop): w = |f|/2^f, the relative error of
        2^f; P of degree 9: 2.20e-16 with exact coefficients, 2.23e-16 after rounding them to
        doubles (degree 10 would give 3.4e-18 and 2.8e-17, for one more multiply-add per
        element: ~2.4 % of the E3 kernel's time);
  expm1 (slut_nl_lanes_expm1, the 4-D table's value base): w = 1/g, the relative error of
        2^f - 1 = f*P(f) down to f = 0; P of degree 10.
The constant term of 2^f is 1 exactly, so 2^0 = 1. Needs python3 and mpmath (Debian:
python3-mpmath); --check exits 77 (CTest's skip code) without mpmath, 1 if the header's
constants are not these.
"""

import argparse
import os
import re
import sys

SKIP = 77

try:
    import mpmath
    from mpmath import mp, mpf
except ImportError as exc:  # pragma: no cover - depends on the machine
    if "--check" in sys.argv[1:]:
        print("skipped: python module mpmath not found (%s; Debian: apt-get install python3-mpmath)" % exc)
        sys.exit(SKIP)
    sys.exit("exp2_minimax.py: needs the python module mpmath (Debian: apt-get install python3-mpmath): %s" % exc)

HERE = os.path.dirname(os.path.abspath(__file__))
HEADER = os.path.join(HERE, "slut_nearlight_lanes.h")
HALF = mpf(1) / 2
# name: (degree of P, weight of P - g)
POLYNOMIALS = {
    "exp2": (9, lambda f: abs(f) / mpmath.power(2, f)),
    "expm1": (10, lambda f: 1 / slope(f)),
}
GRID = 3000  # points of the search for the error's extrema


def p_of(c, f):
    """P(f) = c[0] + c[1] f + ... (c[k] is the coefficient of f^(k+1) in 2^f)."""
    s = mpf(0)
    for ck in reversed(c):
        s = s * f + ck
    return s


def slope(f):
    """(2^f - 1)/f, ln 2 at 0."""
    return (mpmath.power(2, f) - 1) / f if f != 0 else mpmath.log(2)


def weighted_error(c, f, weight):
    """(P - (2^f - 1)/f) * weight(f)."""
    return (p_of(c, f) - slope(f)) * weight(f)


def extrema(c, weight):
    """One point of largest |error| per run of one sign on [-1/2, 1/2] (a grid, then a
    golden-section search next to each grid maximum)."""
    grid = sorted([-HALF + (i + mpf(1) / 7) / GRID for i in range(GRID)] + [-HALF, HALF])
    runs, best = [], None
    for f in grid:
        e = weighted_error(c, f, weight)
        if best is not None and (e > 0) == (best[1] > 0):
            if abs(e) > abs(best[1]):
                best = (f, e)
        else:
            if best is not None:
                runs.append(best)
            best = (f, e)
    runs.append(best)
    points = []
    for f, e in runs:
        lo, hi = max(-HALF, f - mpf(1) / GRID), min(HALF, f + mpf(1) / GRID)
        for _ in range(60):
            m1, m2 = hi - (hi - lo) * mpf("0.6180339887"), lo + (hi - lo) * mpf("0.6180339887")
            if abs(weighted_error(c, m1, weight)) > abs(weighted_error(c, m2, weight)):
                hi = m2
            else:
                lo = m1
        mid = (lo + hi) / 2
        points.append(mid if abs(weighted_error(c, mid, weight)) >= abs(e) else f)
    return points


def minimax(degree, weight):
    """Remez's exchange: the coefficients c of P (c[k] of f^k) and the levelled error."""
    n = degree + 1
    # Start: Chebyshev-like points, none at f = 0 (where the weight vanishes).
    points = [-HALF * mpmath.cos(mpmath.pi * (i + mpf(1) / 5) / (n + mpf(1) / 2)) for i in range(n + 1)]
    for _ in range(40):
        m, b = mpmath.matrix(n + 1, n + 1), mpmath.matrix(n + 1, 1)
        for i, f in enumerate(points):
            for k in range(n):
                m[i, k] = f**k
            m[i, n] = -((-1) ** i) / weight(f)
            b[i] = slope(f)
        solution = mpmath.lu_solve(m, b)
        c, level = [solution[k] for k in range(n)], abs(solution[n])
        found = extrema(c, weight)
        if len(found) < n + 1:
            raise RuntimeError("Remez: %d alternation points, %d needed" % (len(found), n + 1))
        if len(found) > n + 1:  # the n + 1 consecutive points whose smallest |error| is largest
            found = max((found[s : s + n + 1] for s in range(len(found) - n)),
                        key=lambda run: min(abs(weighted_error(c, f, weight)) for f in run))
        worst = max(abs(weighted_error(c, f, weight)) for f in found)
        points = found
        if worst - level <= level * mpf(10) ** -8:
            return c, worst
    raise RuntimeError("Remez did not level the error in 40 exchanges")


def header_coefficients(name):
    """The coefficients in the header between the markers "<name> polynomial begin" and "end"."""
    with open(HEADER, encoding="utf-8") as f:
        text = f.read()
    block = re.search(r"%s polynomial begin(.*?)%s polynomial end" % (name, name), text, re.S)
    if not block:
        sys.exit("exp2_minimax.py: %s has no '%s polynomial begin' ... 'end' block" % (HEADER, name))
    return [float.fromhex(h) for h in re.findall(r"(-?0x1\.[0-9a-f]+p[-+]?[0-9]+)", block.group(1))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare with the header's coefficients")
    args = parser.parse_args()
    mp.dps = 60
    failed = 0
    for name, (degree, weight) in POLYNOMIALS.items():
        c, level = minimax(degree, weight)
        rounded = [float(ck) for ck in c]
        worst_rounded = max(abs(weighted_error([mpf(x) for x in rounded], -HALF + i / mpf(20000), weight))
                            for i in range(20001))
        print("%s: P of degree %d on [-1/2, 1/2], weighted error %s, %s with double coefficients"
              % (name, degree, mpmath.nstr(level, 3), mpmath.nstr(worst_rounded, 3)))
        if args.check:
            have = header_coefficients(name)
            if have != list(reversed(rounded)):
                print("FAIL: %s's %s polynomial is %s, the minimax one %s (highest power first)"
                      % (HEADER, name, [x.hex() for x in have], [x.hex() for x in reversed(rounded)]))
                failed = 1
            else:
                print("ok: the header's %d coefficients are the minimax polynomial's" % len(have))
            continue
        for k in reversed(range(degree + 1)):
            print("    %s, /* f^%d of 2^f */" % (rounded[k].hex(), k + 1))
    return failed


if __name__ == "__main__":
    sys.exit(main())
