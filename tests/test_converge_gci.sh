#!/usr/bin/env bash
# The GCI arithmetic of scripts/converge.sh (scripts/lib/converge_gci.py) against published
# and hand-computed values: Celik et al. (2008), J. Fluids Eng. 130, 078001, Table 1,
# first column (three 2D grids of 18000, 8000, 4500 cells, phi = 6.063, 5.972, 5.863:
# p = 1.53, phi_ext = 6.1685, e_ext = 1.7 %, GCI_fine = 2.2 %), and the cases written out
# below (monotone at the formal order, monotone at another order, oscillatory, diverging,
# two levels, a field). Seconds; no run of rodcontact.
#   bash tests/test_converge_gci.sh <rodcontact> <source dir> <scratch dir>
set -u
src=$2
PY=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
cd "$3" || exit 1
"$PY" - "$src/scripts/lib" << 'EOF'
import math, sys
sys.path.insert(0, sys.argv[1])
import numpy as np
import converge_gci as g

n_checks = n_failed = 0
def check(what, got, expected, tol=1e-12):
    global n_checks, n_failed
    n_checks += 1
    ok = (got == expected) if isinstance(expected, str) else (
        (math.isnan(got) and math.isnan(expected)) or abs(got - expected) <= tol * max(1.0, abs(expected)))
    print(("PASS " if ok else "FAIL ") + what + ("" if ok else f": got {got!r}, expected {expected!r}"))
    n_failed += not ok

# Celik et al. (2008), Table 1, column 1: h = sqrt(A/N) in 2D, so r21 = 1.5, r32 = 4/3
hs = [math.sqrt(76 / n) for n in (4500, 8000, 18000)]
r = g.scalar([5.863, 5.972, 6.063], hs, 2)
check("Celik: p = 1.53", round(r["observed_order"], 2), 1.53)
check("Celik: phi_ext = 6.1685", round(r["extrapolated"], 4), 6.1685)
check("Celik: e_ext21 = 1.7 %", round(100 * abs(r["extrapolated"] - 6.063) / r["extrapolated"], 1), 1.7)
check("Celik: GCI_fine21 = 2.2 %", round(100 * r["gci_rel"], 1), 2.2)
check("Celik: monotone, within the window of the formal order 2", r["status"], "asymptotic")

h = [0.4, 0.2, 0.1]
# phi = 1 + h^2: eps32 = -0.12, eps21 = -0.03, p = ln 4 / ln 2 = 2, phi_ext = (4 * 1.01 - 1.04) / 3 = 1,
# GCI = 1.25 * 0.03 / (4 - 1) = 0.0125
r = g.scalar([1.16, 1.04, 1.01], h, 2)
check("1 + h^2: p = 2", r["observed_order"], 2.0, 1e-9)
check("1 + h^2: extrapolate 1", r["extrapolated"], 1.0, 1e-9)
check("1 + h^2: GCI = 1.25 * 0.03 / 3", r["gci_abs"], 0.0125, 1e-9)
check("1 + h^2: gci_rel = GCI / 1.01", r["gci_rel"], 0.0125 / 1.01, 1e-9)
check("1 + h^2: asymptotic", r["status"], "asymptotic")
# phi = 1 + h against formal order 2: p = 1, not asymptotic: Fs = 3, p_used = min(1, 2) = 1,
# delta = max(0.1, 0.2 / 2^1) = 0.1, GCI = 3 * 0.1 / (2 - 1) = 0.3, phi_ext = 2 * 1.1 - 1.2 = 1
r = g.scalar([1.4, 1.2, 1.1], h, 2)
check("1 + h, formal 2: p = 1", r["observed_order"], 1.0, 1e-9)
check("1 + h, formal 2: not_asymptotic", r["status"], "not_asymptotic")
check("1 + h, formal 2: GCI = 3 * 0.1 / 1", r["gci_abs"], 0.3, 1e-9)
check("1 + h, formal 2: extrapolate 1", r["extrapolated"], 1.0, 1e-9)
# the same against formal order 1: asymptotic, GCI = 1.25 * 0.1 / 1
r = g.scalar([1.4, 1.2, 1.1], h, 1)
check("1 + h, formal 1: asymptotic", r["status"], "asymptotic")
check("1 + h, formal 1: GCI = 1.25 * 0.1 / 1", r["gci_abs"], 0.125, 1e-9)
# oscillatory: 1.16, 0.96, 1.01: eps32 = -0.2, eps21 = +0.05, p = ln 4 / ln 2 = 2, Fs = 3,
# delta = max(0.05, 0.2 / 4) = 0.05, GCI = 3 * 0.05 / 3 = 0.05
r = g.scalar([1.16, 0.96, 1.01], h, 2)
check("oscillatory: status", r["status"], "oscillatory")
check("oscillatory: p = 2", r["observed_order"], 2.0, 1e-9)
check("oscillatory: GCI = 3 * 0.05 / 3", r["gci_abs"], 0.05, 1e-9)
# oscillatory at a low order: 1.2, 0.9, 1.1: eps32 = -0.3, eps21 = +0.2, p = ln 1.5 / ln 2 =
# 0.585, delta = max(0.2, 0.3 / 2^p) = 0.2; the order-based band 3 * 0.2 / (2^p - 1) = 1.2 is
# capped at Fs |eps21| = 0.6 (the exact value lies between the two finest levels)
r = g.scalar([1.2, 0.9, 1.1], h, 2)
check("oscillatory, p < 1: status", r["status"], "oscillatory")
check("oscillatory, p < 1: p = ln 1.5 / ln 2", r["observed_order"], math.log(1.5) / math.log(2), 1e-9)
check("oscillatory, p < 1: band capped at 3 |eps21| = 0.6", r["gci_abs"], 0.6, 1e-9)
# below P_MIN: 1.2, 0.85, 1.1: eps32 = -0.35, eps21 = 0.25, p = 0.485, p_used = 0.5:
# 3 * max(0.25, 0.35 / sqrt 2) / (sqrt 2 - 1) = 1.81 capped at 3 * 0.25 = 0.75
r = g.scalar([1.2, 0.85, 1.1], h, 2)
check("oscillatory, p < P_MIN: band capped at 3 |eps21| = 0.75", r["gci_abs"], 0.75, 1e-9)
# diverging: the differences grow (0.1 then 0.2): no extrapolate, no band
r = g.scalar([1.0, 1.1, 1.3], h, 2)
check("diverging: status", r["status"], "diverging")
check("diverging: no band", r["gci_abs"], math.nan)
check("diverging: no extrapolate", r["extrapolated"], math.nan)
# two levels: the formal order, Fs = 3: GCI = 3 * 0.03 / 3, phi_ext = (4 * 1.01 - 1.04) / 3
r = g.scalar([1.04, 1.01], [0.2, 0.1], 2)
check("two levels: not_asymptotic", r["status"], "not_asymptotic")
check("two levels: GCI = 3 * 0.03 / 3", r["gci_abs"], 0.03, 1e-9)
check("two levels: extrapolate 1", r["extrapolated"], 1.0, 1e-9)
# the two finest levels agree but the next does not: a band all the same (from eps32)
r = g.scalar([1.16, 1.01, 1.01], h, 2)
check("eps21 = 0, eps32 != 0: not_asymptotic", r["status"], "not_asymptotic")
check("eps21 = 0: GCI = 3 * (0.15 / 4) / 3", r["gci_abs"], 0.15 / 4, 1e-9)
# levels that agree to round-off (differences 3e-14 and 1e-13, below ROUNDOFF * |phi|): the band
# is of their differences' size, 1.25 * 3e-14 / (2^2 - 1), not one made up from the formal order
r = g.scalar([1.0 + 1.3e-13, 1.0 + 3e-14, 1.0], h, 2)
check("round-off agreement: unchanged (no order observed; never asymptotic)", r["status"], "unchanged")
check("round-off agreement: the order is nan", math.isnan(r["observed_order"]), True)
check("round-off agreement: band / (1.25 * 3e-14 / 3) = 1 (to the 1 % of 3e-14's rounding)",
      r["gci_abs"] / (1.25 * 3e-14 / 3), 1.0, 1e-2)
# Celik's iteration with r21 != r32 on exact second-order data phi = 2 + h^2
hv = [0.3, 0.2, 0.1]
r = g.scalar([2 + x * x for x in hv], hv, 2)
check("r21 = 2, r32 = 1.5, phi = 2 + h^2: p = 2", r["observed_order"], 2.0, 1e-8)
check("r21 = 2, r32 = 1.5, phi = 2 + h^2: extrapolate 2", r["extrapolated"], 2.0, 1e-8)
# a field f = sin(pi x) + h^2 x on x = 0..1: eps21 = (0.04 - 0.01) x, ||x|| = 1/sqrt(3)
# (trapezoidal rule on 1001 nodes: ||x||^2 = 1/3 + 1/(6 * 1000^2)); band 1.25 * 0.03 ||x|| / 3
x = np.linspace(0, 1, 1001)
norm_x = math.sqrt(1 / 3 + 1 / (6 * 1000 ** 2))
r = g.field([np.sin(np.pi * x) + hh * hh * x for hh in h], h, x, 2)
check("field: p = 2", r["observed_order"], 2.0, 1e-9)
check("field: band 1.25 * 0.03 ||x|| / 3", r["gci_abs"], 1.25 * 0.03 * norm_x / 3, 1e-9)
check("field: fine = ||sin(pi x) + 0.01 x||", r["fine"], g.l2(np.sin(np.pi * x) + 0.01 * x, x), 1e-12)
check("field: extrapolate = ||sin(pi x)||", r["extrapolated"], g.l2(np.sin(np.pi * x), x), 1e-9)
check("field: asymptotic", r["status"], "asymptotic")
r = g.field([np.sin(np.pi * x) + s * hh * hh * x for hh, s in zip(h, (1, -1, 1))], h, x, 2)
check("field whose differences change sign: oscillatory", r["status"], "oscillatory")
# a field oscillating at a low order: sin(pi x) + c_k x with c = 0.3, -0.2, 0.1 (eps32 = -0.5 x,
# eps21 = 0.3 x, p = ln(5/3) / ln 2 < 1): the band is 3 ||eps21|| = 0.9 ||x||
r = g.field([np.sin(np.pi * x) + c * x for c in (0.3, -0.2, 0.1)], h, x, 2)
check("field oscillating at p < 1: oscillatory", r["status"], "oscillatory")
check("field oscillating at p < 1: band 3 ||eps21|| = 0.9 ||x||", r["gci_abs"], 0.9 * norm_x, 1e-9)

print(f"test_converge_gci: {n_failed} of {n_checks} checks failed")
sys.exit(1 if n_failed else 0)
EOF
