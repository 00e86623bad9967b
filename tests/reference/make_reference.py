#!/usr/bin/env python3
"""30-digit reference values for scatterlut's tests (tests/reference/README.md).

    python3 tests/reference/make_reference.py            # writes F_ref.json, N_ref.json, physical_ref.json, hg_ref.json, surface_ref.json
    python3 tests/reference/make_reference.py --check    # recomputes a subset, compares with the files

Every value is an integral computed with mpmath by adaptive tanh-sinh quadrature on panels
cut at the integrand's features (boundary layers, near-singular peaks, e-folding lengths),
and computed a second time by an independent route (a closed form, or Gauss-Legendre
quadrature on a different set of panels). The two must agree to AGREE_REL (relative) or the
script stops with an error and writes nothing. Values are written as decimal strings with
25 significant digits. Inputs are IEEE doubles, taken exactly (v = pi/2 means the double
nearest pi/2, which lies 6.1e-17 below it). Needs python3 and mpmath (>= 1.2.1).

The computation is in modules beside this script, imported by it: ref_common.py (precisions,
the cross-check, the quadratures and their panels), ref_isotropic.py (F and its tail, N, H, E,
the airlight and near-light radiance), ref_anisotropic.py (the same with a Henyey-Greenstein
phase), ref_surface.py (the surface terms) and ref_inputs.py (every input, and --check's order).
"""

import argparse
import json
import os
import sys
import tempfile
import time

SKIP = 77  # CTest's SKIP_RETURN_CODE for --check

try:
    import mpmath
    from mpmath import mp, mpf
except ImportError as exc:  # pragma: no cover - depends on the machine
    if "--check" in sys.argv[1:]:
        print("skipped: python module mpmath not found (%s; Debian: apt-get install python3-mpmath)" % exc)
        sys.exit(SKIP)
    sys.exit("make_reference.py: needs the python module mpmath (Debian: apt-get install python3-mpmath): %s" % exc)

sys.dont_write_bytecode = True  # no __pycache__ in the source tree (the modules below sit beside this script)

from ref_common import CHECK_REL, INF, OUT_DIGITS, WORK_DPS, WORST, ReferenceError, rel_diff  # noqa: E402
from ref_isotropic import F_point, N_point, airlight_case, near_light_case  # noqa: E402
from ref_anisotropic import hg_airlight_case, hg_near_light_case  # noqa: E402
from ref_surface import surface_case  # noqa: E402
from ref_inputs import (AIRLIGHT_INPUTS, CHECK_FIRST, F_INPUTS, HG_AIRLIGHT_INPUTS, HG_NEAR_LIGHT_INPUTS,  # noqa: E402
                        N_INPUTS, NEAR_LIGHT_INPUTS, SURFACE_INPUTS, check_order)

HERE = os.path.dirname(os.path.abspath(__file__))


# --------------------------------------------------------------------------------------------
# Output

def fmt(x):
    """25 significant digits (mpmath's shortest form: fixed or exponent)."""
    return mpmath.nstr(x, OUT_DIGITS)


def json_number(x):
    return "inf" if x == INF else x


def F_record(p):
    return {"u": p["u"], "v": p["v"], "F": fmt(p["F"]), "tail": fmt(p["tail"])}


def N_record(p):
    return {"T": p["T"], "g": p["g"], "r": p["r"], "S": json_number(p["S"]),
            "N": fmt(p["N"]), "H": fmt(p["H"]), "E": fmt(p["E"])}


def physical_record(c):
    out = {}
    for k, v in c.items():
        if k in ("L", "G", "E"):
            out[k] = fmt(v)
        elif k == "length":
            out[k] = json_number(v)
        else:
            out[k] = v
    return out


F_DEFINITION = "F(u,v)=int_0^v exp(-u tan x) dx; tail=int_v^{pi/2} exp(-u tan x) dx (Sun et al. 2005); u, v doubles taken exactly"
N_DEFINITION = ("N(T,g,r,S)=int_0^S exp(-t-h t/(t+T r))/h^2 dt, h^2=t^2+T^2+2tTg; H=int_0^S h^-2 dt; E=N/H "
                "(Gath 2008 4.2); S='inf' = thick")
PHYSICAL_CONVENTIONS = ("airlight: gamma = angle between view direction and direction viewer->light, "
                        "d(x)^2 = x^2 + D^2 - 2 x D cos(gamma); near_light: plane through origin with outward normal, "
                        "medium below, eye_dir from entry point towards viewer, light_pos relative to entry point, "
                        "length = path inside ('inf' = thick), light below the plane gives 0; isotropic phase 1/(4 pi); "
                        "L in W/(m^2 sr) for intensity I0 in W/sr, sigma in 1/m, lengths in m")
HG_CONVENTIONS = ("as physical_ref.json, with the Henyey-Greenstein phase p(theta) = (1 - g^2)/(4 pi (1 + g^2 - "
                  "2 g cos theta)^{3/2}), g = phase_g (> 0 forward), theta between the light's propagation direction "
                  "at the point (light -> point) and the direction from the point to the viewer: airlight cos theta = "
                  "(D cos(gamma) - x)/d(x), near_light cos theta = -(x + eye_dir.light_pos)/d(x)")

SURFACE_CONVENTIONS = ("surface point in an unbounded medium with isotropic phase 1/(4 pi), point light of intensity "
                       "I0 (W/sr) at distance D (m); theta = angle between the normal (quantity surface) or the mirror "
                       "direction rho (surface_specular) and the direction from the point to the light; L_in(omega) = "
                       "airlight along the infinite ray from the point in direction omega; surface: E = int_{n.omega>0} "
                       "L_in n.omega d omega; surface_specular: E = int L_in max(omega.rho, 0)^exponent d omega (no "
                       "horizon clipping, Sun et al. 2005); both W/m^2; G = E 4 pi D/(sigma_s I0), dimensionless")


def compute(kind, i):
    if kind == "F":
        return F_point(*F_INPUTS[i])
    if kind == "N":
        return N_point(*N_INPUTS[i])
    if kind == "airlight":
        return airlight_case(*AIRLIGHT_INPUTS[i])
    if kind == "hg_airlight":
        return hg_airlight_case(*HG_AIRLIGHT_INPUTS[i])
    if kind == "hg_near_light":
        return hg_near_light_case(*HG_NEAR_LIGHT_INPUTS[i])
    if kind == "surface":
        return surface_case(*SURFACE_INPUTS[i])
    return near_light_case(*NEAR_LIGHT_INPUTS[i])


def record(kind, value):
    return {"F": F_record, "N": N_record}.get(kind, physical_record)(value)


def generate_all(log):
    files = {}
    for kind, count in (("F", len(F_INPUTS)), ("N", len(N_INPUTS)), ("airlight", len(AIRLIGHT_INPUTS)),
                        ("near_light", len(NEAR_LIGHT_INPUTS)), ("hg_airlight", len(HG_AIRLIGHT_INPUTS)),
                        ("hg_near_light", len(HG_NEAR_LIGHT_INPUTS)), ("surface", len(SURFACE_INPUTS))):
        t0 = time.time()
        files[kind] = [record(kind, compute(kind, i)) for i in range(count)]
        log("%-10s %4d values  %6.1f s" % (kind, count, time.time() - t0))
    return {
        "F_ref.json": {"definition": F_DEFINITION, "points": files["F"]},
        "N_ref.json": {"definition": N_DEFINITION, "points": files["N"]},
        "physical_ref.json": {"conventions": PHYSICAL_CONVENTIONS, "cases": files["airlight"] + files["near_light"]},
        "hg_ref.json": {"conventions": HG_CONVENTIONS, "cases": files["hg_airlight"] + files["hg_near_light"]},
        "surface_ref.json": {"conventions": SURFACE_CONVENTIONS, "cases": files["surface"]},
    }


def dump(doc):
    return json.dumps(doc, indent=1, ensure_ascii=False) + "\n"


def write_atomically(directory, docs):
    """All files are computed before any is written; each is renamed into place."""
    for name, doc in docs.items():
        fd, tmp = tempfile.mkstemp(prefix="." + name, dir=directory)
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(dump(doc))
            os.chmod(tmp, 0o644)
            os.replace(tmp, os.path.join(directory, name))
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise


# --------------------------------------------------------------------------------------------
# --check

def committed_entries(directory):
    """The committed files' entries by (kind, index), after checking that their inputs are this
    script's inputs, in the same order."""
    def load(name):
        path = os.path.join(directory, name)
        try:
            with open(path, encoding="utf-8") as f:
                return json.load(f)
        except OSError as exc:
            raise ReferenceError("cannot read %s: %s" % (path, exc))
        except ValueError as exc:
            raise ReferenceError("%s is not valid JSON: %s" % (path, exc))
    def entries(name, key):
        doc = load(name)
        if not isinstance(doc, dict) or not isinstance(doc.get(key), list) or \
                not all(isinstance(e, dict) for e in doc[key]):
            raise ReferenceError("%s: expected an object with a \"%s\" array of objects" % (os.path.join(directory, name), key))
        return doc[key]
    F = entries("F_ref.json", "points")
    N = entries("N_ref.json", "points")
    phys = entries("physical_ref.json", "cases")
    air = [c for c in phys if c.get("quantity") == "airlight"]
    near = [c for c in phys if c.get("quantity") == "near_light"]
    hg = entries("hg_ref.json", "cases")
    hg_air = [c for c in hg if c.get("quantity") == "airlight"]
    hg_near = [c for c in hg if c.get("quantity") == "near_light"]
    surface = entries("surface_ref.json", "cases")
    expected = {
        "F": [{"u": u, "v": v} for u, v in F_INPUTS],
        "N": [{"T": T, "g": g, "r": r, "S": json_number(S)} for T, g, r, S in N_INPUTS],
        "airlight": [dict(zip(("sigma_s", "sigma_a", "intensity", "distance", "gamma", "length"), c)) for c in AIRLIGHT_INPUTS],
        "near_light": [{"sigma_s": c[0], "sigma_a": c[1], "intensity": c[2], "normal": list(c[3]), "eye_dir": list(c[4]),
                        "light_pos": list(c[5]), "length": json_number(c[6])} for c in NEAR_LIGHT_INPUTS],
        "hg_airlight": [dict(zip(("phase_g", "sigma_s", "sigma_a", "intensity", "distance", "gamma", "length"),
                                 c[:6] + (json_number(c[6]),))) for c in HG_AIRLIGHT_INPUTS],
        "hg_near_light": [{"phase_g": c[0], "sigma_s": c[1], "sigma_a": c[2], "intensity": c[3], "normal": list(c[4]),
                           "eye_dir": list(c[5]), "light_pos": list(c[6]), "length": json_number(c[7])}
                          for c in HG_NEAR_LIGHT_INPUTS],
        "surface": [dict(zip(("quantity", "sigma_s", "sigma_a", "intensity", "distance", "theta"), c[:6]),
                         **({"exponent": c[6]} if c[0] == "surface_specular" else {})) for c in SURFACE_INPUTS],
    }
    have = {"F": F, "N": N, "airlight": air, "near_light": near, "hg_airlight": hg_air, "hg_near_light": hg_near,
            "surface": surface}
    names = {"F": "F_ref.json", "N": "N_ref.json", "airlight": "physical_ref.json", "near_light": "physical_ref.json",
             "hg_airlight": "hg_ref.json", "hg_near_light": "hg_ref.json", "surface": "surface_ref.json"}
    for kind, want in expected.items():
        got = have[kind]
        if len(got) != len(want):
            raise ReferenceError("%s: %d %s entries, the script has %d inputs: rerun make_reference.py"
                                 % (names[kind], len(got), kind, len(want)))
        for i, (g, w) in enumerate(zip(got, want)):
            for k, v in w.items():
                if g.get(k) != v:
                    raise ReferenceError("%s: %s entry %d has %s = %r, the script's input is %r: rerun make_reference.py"
                                         % (names[kind], kind, i, k, g.get(k), v))
    return have, names


def run_check(directory, n, log):
    have, names = committed_entries(directory)
    worst = mpf(0)
    failures = []
    t0 = time.time()
    for kind, i in check_order(n):
        fresh = record(kind, compute(kind, i))
        old = have[kind][i]
        for key in ("F", "tail", "N", "H", "E", "L", "G"):
            if key not in fresh:
                continue
            try:
                b = mpf(old[key])
            except (KeyError, TypeError, ValueError):
                failures.append("%s: %s entry %d: %s missing or not a decimal string (%r)"
                                % (names[kind], kind, i, key, old.get(key)))
                continue
            a = mpf(fresh[key])
            e = rel_diff(a, b)
            worst = max(worst, e)
            if e > CHECK_REL:
                failures.append("%s: %s entry %d (%s): %s = %s recomputed, %s committed (relative %s > %g)"
                                % (names[kind], kind, i, json.dumps({k: v for k, v in old.items() if k not in ("F", "tail", "N", "H", "E", "L", "G")}),
                                   key, fresh[key], old[key], mpmath.nstr(e, 3), CHECK_REL))
    log("checked %d points in %.1f s; worst relative difference %s" % (n, time.time() - t0, mpmath.nstr(worst, 3)))
    return failures


def main(argv):
    ap = argparse.ArgumentParser(description="Compute (or --check) the 30-digit reference values of tests/reference.")
    ap.add_argument("--check", action="store_true", help="recompute a subset and compare it with the committed files")
    ap.add_argument("--points", type=int, default=len(CHECK_FIRST), metavar="N",
                    help="--check: how many values to recompute (default %(default)s: the hard points)")
    ap.add_argument("--dir", default=HERE, help="where the JSON files are read and written (default: this script's directory)")
    args = ap.parse_args(argv)
    total = len(F_INPUTS) + len(N_INPUTS) + len(AIRLIGHT_INPUTS) + len(NEAR_LIGHT_INPUTS) + len(HG_AIRLIGHT_INPUTS) + \
        len(HG_NEAR_LIGHT_INPUTS) + len(SURFACE_INPUTS)
    if not 1 <= args.points <= total:
        ap.error("--points: expected an integer in [1, %d], got %d" % (total, args.points))
    mp.dps = WORK_DPS

    def log(msg):
        print(msg, file=sys.stderr if not args.check else sys.stdout, flush=True)

    log("mpmath %s (%s backend), %d digits" % (mpmath.__version__, mpmath.libmp.BACKEND, WORK_DPS))
    try:
        if args.check:
            failures = run_check(args.dir, args.points, log)
            for f in failures:
                print("make_reference.py --check: " + f, file=sys.stderr)
            if failures:
                return 1
            print("make_reference.py --check: %d values agree with the committed files (<= %g relative)" % (args.points, CHECK_REL))
            return 0
        t0 = time.time()
        docs = generate_all(log)
        write_atomically(args.dir, docs)
        for key in sorted(WORST):
            log("worst relative difference, %-55s %s" % (key + ":", mpmath.nstr(WORST[key], 3)))
        log("wrote %s to %s in %.0f s" % (", ".join(docs), args.dir, time.time() - t0))
        return 0
    except ReferenceError as exc:
        print("make_reference.py: %s" % exc, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
