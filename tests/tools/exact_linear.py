"""Exact solution of the linear problem (2.11), (2.13), (2.15) without contact, by separation
of variables, and the relative L2 error of a rodcontact run against it.

Before the rod first touches the obstacle the model is linear. With lambda_k = (k + 1/2) pi,

    u, v, q, eta = sum_k (.)_k(t) sin(lambda_k x)     (zero at x = 0)
    theta, P     = sum_k (.)_k(t) cos(lambda_k x)     (zero at x = 1; also u_x(1) = 0, so sigma(1) = 0)

and (2.11) falls apart into one linear ODE system per mode. rho = 1.2e-17 is taken in its
quasi-static limit rho -> 0 (the neglected inertia changes the solution by O(rho)): the
momentum balance becomes the algebraic relation
    varpi w' = -alpha w + gamma1 T + gamma2 p,      w = lambda a (the amplitude of u_x),
so u1 does not enter (its momentum rho u1 is of order 1e-16). The remaining system in
y = (w, T, p, Q, E) (Q, E dropped when tau0 = 0 or tau = 0: Fourier's and Fick's laws give
Q = lambda T, E = lambda p) is
    c T' + d p' = -lambda Q - gamma1 w'        (2.11)_2
    d T' + r p' = -hbar lambda E - gamma2 w'   (2.11)_4
    tau0 Q' = -Q + lambda T                    (2.11)_3
    tau E'  = -E + lambda p                    (2.11)_5
and y(t) = expm(A t) y(0), computed for all modes at once (scipy.linalg.expm on a stack of
small matrices). The initial data (polynomials and steps of &initial) are projected on the
modes exactly (closed-form integrals), so discontinuous pulses need many modes: the
series is summed with K modes at the K midpoints x_j = (j + 1/2)/K by a type-4 DST/DCT,
and L2 norms use the midpoint rule there. The truncation error (a jump of height J leaves
an L2 error of about 0.45 J / sqrt(K)) is printed by `--self-check`.

As a module:
    ex = ExactLinear.from_attrs(h5file.attrs, n_modes=2**18)
    fields = ex.fields(t)              # dict u, v, theta, P, q, eta on ex.x (midpoints)
    err = ex.rel_l2(fields, x_nodes, {"u": u_nodes, ...})   # relative L2 per field
    cache = Cache(2**18); ex, fields = cache.get(attrs, t)  # each model and t computed once
As a program:
    <python with scipy, h5py> tests/tools/exact_linear.py RUN.h5 [--times t1,t2,...] [--modes K]
    <python> tests/tools/exact_linear.py --self-check
prints the relative L2 error of each field of RUN.h5 at the snapshot times (default: every
snapshot before the first contact). Exit status 0, 1 (a check failed or a time is after
contact), 2 usage / not a rodcontact file.
"""

import argparse
import math
import os
import sys

import numpy as np
import scipy.fft
import scipy.linalg

FIELDS = ["u", "v", "theta", "P", "q", "eta"]
SINE_FIELDS = ("u", "v", "q", "eta")          # expanded in sin(lambda x); theta, P in cos


def poly_projection(coeffs, lam, kind):
    """2 * integral_0^1 (sum_n coeffs[n] x^n) phi(lambda x) dx, phi = sin or cos, for
    lambda = (k + 1/2) pi (so sin(lambda) = (-1)^k, cos(lambda) = 0): the integrals
    I_n = int_0^1 x^n cos / sin by the recursion I_n^c = sin(lam)/lam - n/lam I_{n-1}^s,
    I_n^s = -cos(lam)/lam + n/lam I_{n-1}^c (stable: lam >= pi/2 and n <= 8)."""
    k = np.rint(lam / math.pi - 0.5)
    s1 = np.where(k % 2 == 0, 1.0, -1.0)      # sin(lambda)
    ic = s1 / lam                             # I_0^c
    is_ = 1.0 / lam                           # I_0^s (cos(lambda) = 0)
    total = np.zeros_like(lam)
    for n, a in enumerate(coeffs):
        if n > 0:
            ic, is_ = s1 / lam - n / lam * is_, n / lam * ic
        if a != 0.0:
            total += a * (ic if kind == "cos" else is_)
    return 2.0 * total


def step_projection(amp, x_end, lam, kind):
    """2 * integral_0^x_end amp phi(lambda x) dx."""
    if amp == 0.0 or x_end <= 0.0:
        return np.zeros_like(lam)
    if kind == "cos":
        return 2.0 * amp * np.sin(lam * x_end) / lam
    return 2.0 * amp * (1.0 - np.cos(lam * x_end)) / lam


class ExactLinear:
    """Modal solution of the contact-free problem; see the module docstring."""

    def __init__(self, model, initial, n_modes=2**18):
        self.m = dict(model)
        if self.m["varpi"] <= 0.0:
            raise ValueError("the quasi-static modal solution needs varpi > 0")
        self.K = int(n_modes)
        self.lam = (np.arange(self.K) + 0.5) * math.pi
        self.x = (np.arange(self.K) + 0.5) / self.K      # midpoints: the DST-IV/DCT-IV grid
        self.has_q = self.m["tau0"] > 0.0
        self.has_eta = self.m["tau"] > 0.0
        self.A, self.rw = self._matrices()
        self.y0 = self._initial(initial)
        self._diagonalise()

    @classmethod
    def from_attrs(cls, attrs, n_modes=2**18):
        """From the root attributes of a rodcontact HDF5 file (model.*, initial.*)."""
        model = {k: float(attrs["model." + k]) for k in
                 ("alpha", "varpi", "gamma1", "gamma2", "c", "d", "r", "hbar", "tau0", "tau")}
        initial = {}
        tables = [k for k in attrs if k.startswith("initial.") and k.endswith("_table")]
        if tables:
            raise ValueError("initial data from a table (%s): only polynomials and steps are "
                             "projected on the modes" % ", ".join(sorted(tables)))
        for name in ("u0", "u1", "theta0", "p0", "q0", "eta0"):
            initial[name + "_poly"] = [float(v) for v in np.atleast_1d(attrs["initial.%s_poly" % name])]
        for name in ("theta0", "p0"):
            initial[name + "_step"] = [float(v) for v in np.atleast_1d(attrs["initial.%s_step" % name])]
        return cls(model, initial, n_modes)

    # -- the modal system ---------------------------------------------------------------
    def _index(self):
        idx = {"w": 0, "T": 1, "p": 2}
        n = 3
        if self.has_q:
            idx["Q"] = n
            n += 1
        if self.has_eta:
            idx["E"] = n
            n += 1
        return idx, n

    def _matrices(self):
        m, lam, K = self.m, self.lam, self.K
        idx, n = self._index()
        self.idx, self.n = idx, n
        # w' = rw . y  (quasi-static momentum balance)
        rw = np.zeros((K, n))
        rw[:, idx["w"]] = -m["alpha"] / m["varpi"]
        rw[:, idx["T"]] = m["gamma1"] / m["varpi"]
        rw[:, idx["p"]] = m["gamma2"] / m["varpi"]
        # right-hand sides of c T' + d p' and d T' + r p'
        rhs_t = -m["gamma1"] * rw
        rhs_p = -m["gamma2"] * rw
        if self.has_q:
            rhs_t[:, idx["Q"]] -= lam
        else:                                   # Fourier: q = -theta_x -> Q = lambda T
            rhs_t[:, idx["T"]] -= lam * lam
        if self.has_eta:
            rhs_p[:, idx["E"]] -= m["hbar"] * lam
        else:                                   # Fick: eta = -P_x -> E = lambda p
            rhs_p[:, idx["p"]] -= m["hbar"] * lam * lam
        det = m["c"] * m["r"] - m["d"] ** 2     # > 0 by (2.16)
        A = np.zeros((K, n, n))
        A[:, idx["w"], :] = rw
        A[:, idx["T"], :] = (m["r"] * rhs_t - m["d"] * rhs_p) / det
        A[:, idx["p"], :] = (-m["d"] * rhs_t + m["c"] * rhs_p) / det
        if self.has_q:
            A[:, idx["Q"], idx["Q"]] = -1.0 / m["tau0"]
            A[:, idx["Q"], idx["T"]] = lam / m["tau0"]
        if self.has_eta:
            A[:, idx["E"], idx["E"]] = -1.0 / m["tau"]
            A[:, idx["E"], idx["p"]] = lam / m["tau"]
        return A, rw

    def _initial(self, ini):
        lam = self.lam
        y = np.zeros((self.K, self.n))
        get = lambda key: ini.get(key, [0.0])
        y[:, self.idx["w"]] = lam * poly_projection(get("u0_poly"), lam, "sin")
        theta = poly_projection(get("theta0_poly"), lam, "cos")
        p = poly_projection(get("p0_poly"), lam, "cos")
        st, sp = get("theta0_step") + [0.0, 0.0], get("p0_step") + [0.0, 0.0]
        theta = theta + step_projection(st[0], st[1], lam, "cos")
        p = p + step_projection(sp[0], sp[1], lam, "cos")
        y[:, self.idx["T"]] = theta
        y[:, self.idx["p"]] = p
        if self.has_q:
            y[:, self.idx["Q"]] = poly_projection(get("q0_poly"), lam, "sin")
        if self.has_eta:
            y[:, self.idx["E"]] = poly_projection(get("eta0_poly"), lam, "sin")
        return y

    def _diagonalise(self):
        """A = V diag(mu) V^-1 for every mode at once (batched eig): y(t) = V (e^{mu t} z0),
        z0 = V^-1 y0. Modes whose eigenvector matrix is ill-conditioned (near a double
        eigenvalue: a Cattaneo pair near critical damping) use expm instead."""
        mu, V = np.linalg.eig(self.A)
        cond = np.linalg.cond(V)
        self.by_expm = np.nonzero(~np.isfinite(cond) | (cond > 1e6))[0]
        good = np.ones(self.K, dtype=bool)
        good[self.by_expm] = False
        V[~good] = np.eye(self.n)
        mu[~good] = 0.0
        self.mu, self.V = mu, V
        self.z0 = np.linalg.solve(V, self.y0.astype(complex)[..., None])[..., 0]

    def state(self, t, use_expm=False):
        """y(t) for every mode (K x n)."""
        if use_expm:
            return np.einsum("kij,kj->ki", scipy.linalg.expm(self.A * t), self.y0)
        y = np.einsum("kij,kj->ki", self.V, np.exp(self.mu * t) * self.z0).real
        if self.by_expm.size:
            k = self.by_expm
            y[k] = np.einsum("kij,kj->ki", scipy.linalg.expm(self.A[k] * t), self.y0[k])
        return y

    def modes(self, t):
        """Modal amplitudes of u, v, theta, P, q, eta at time t (arrays of length K)."""
        y = self.y0 if t == 0.0 else self.state(t)
        lam, idx = self.lam, self.idx
        w = y[:, idx["w"]]
        out = {"u": w / lam, "v": np.einsum("ki,ki->k", self.rw, y) / lam,
               "theta": y[:, idx["T"]], "P": y[:, idx["p"]]}
        out["q"] = y[:, idx["Q"]] if self.has_q else lam * y[:, idx["T"]]
        out["eta"] = y[:, idx["E"]] if self.has_eta else lam * y[:, idx["p"]]
        return out

    def fields(self, t):
        """The six fields at time t on the midpoints self.x."""
        out = {}
        for name, c in self.modes(t).items():
            kind = 4
            if name in SINE_FIELDS:
                out[name] = scipy.fft.dst(c, type=kind) / 2.0
            else:
                out[name] = scipy.fft.dct(c, type=kind) / 2.0
        return out

    def rel_l2(self, exact, x_nodes, nodal):
        """Relative L2 error of P1 nodal values (linear interpolation between x_nodes)
        against the exact fields, midpoint rule on self.x. Returns {field: error}."""
        err = {}
        for name, values in nodal.items():
            fh = np.interp(self.x, x_nodes, values)
            ref = math.sqrt(np.mean(exact[name] ** 2))
            err[name] = math.sqrt(np.mean((fh - exact[name]) ** 2)) / ref if ref > 0 else float("nan")
        return err


class Cache:
    """Exact solutions for the runs of a study: one ExactLinear per model and initial data
    (the model.* and initial.* root attributes), and its fields per t, each computed once."""

    def __init__(self, n_modes=2**18):
        self.n_modes = n_modes
        self.models, self.cache = {}, {}

    @staticmethod
    def key(attrs):
        return tuple(sorted((k, str(np.asarray(v).tolist())) for k, v in attrs.items()
                            if k.startswith("model.") or k.startswith("initial.")))

    def get(self, attrs, t):
        """(ExactLinear, its fields at t) for a run with the root attributes attrs."""
        key = self.key(attrs)
        if key not in self.models:
            self.models[key] = ExactLinear.from_attrs(attrs, self.n_modes)
        if (key, t) not in self.cache:
            self.cache[(key, t)] = self.models[key].fields(t)
        return self.models[key], self.cache[(key, t)]


def first_contact_time(f):
    pen = f["series/penetration"][:]
    on = np.nonzero(pen > 0.0)[0]
    return float(f["series/t"][on[0]]) if on.size else math.inf


def errors_of_run(path, times=None, n_modes=2**18):
    """{t: {field: relative L2 error}} of the run file at the given snapshot times (default:
    every snapshot with 0 < t < first contact). Raises ValueError for a time at or after
    the first contact or without a snapshot."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                    'scripts', 'lib'))
    import rodrun     # here: the self-check needs no h5py
    with rodrun.open_run(path) as f:
        t_contact = first_contact_time(f)
        ts = f["snapshots/t"][:]
        if times is None:
            times = [float(t) for t in ts if 0.0 < t < t_contact]
        ex = ExactLinear.from_attrs(rodrun.attributes(f), n_modes)
        out = {}
        for t in times:
            if t >= t_contact:
                raise ValueError(f"t = {t:g} is not before the first contact (t = {t_contact:g})")
            k = rodrun.nearest(ts, t)
            if abs(ts[k] - t) > 1e-9 * max(1.0, t):
                raise ValueError(f"{path} has no snapshot at t = {t:g}")
            x, nodal = rodrun.snapshot(f, k, FIELDS)
            out[t] = ex.rel_l2(ex.fields(float(ts[k])), x, nodal)
    return out


def self_check():
    """Checks of the module on its own: the projection of the initial data reproduces it,
    the modal system satisfies the PDE residual, truncation error versus K."""
    ok = True
    model = dict(alpha=0.0163, varpi=0.1, gamma1=0.01931, gamma2=4.635e-4, c=1.0136,
                 d=0.00251, r=4.635e-4, hbar=0.03058, tau0=0.02, tau=0.2)
    poly = dict(theta0_poly=[0, 40, -80, 40], p0_poly=[0, 0, 20, -40, 20], u0_poly=[0, 0.1, -0.05])
    ex = ExactLinear(model, poly, 2**14)
    f0 = ex.fields(0.0)
    x = ex.x
    for name, c, ref in (("theta", [0, 40, -80, 40], f0["theta"]), ("P", [0, 0, 20, -40, 20], f0["P"]),
                         ("u", [0, 0.1, -0.05], f0["u"])):
        exact = np.polyval(list(reversed(c)), x)
        e = np.abs(ref - exact).max() / np.abs(exact).max()
        print(f"projection of the polynomial {name}0 (2^14 modes): max relative error {e:.2e}")
        ok &= e < 1e-3
    # time derivative by central differences against A y: the modal ODE (sanity of expm)
    t, dt = 0.05, 1e-6
    ym, yp = ex.modes(t - dt), ex.modes(t + dt)
    y = ex.modes(t)
    # (2.11)_3 in modal form: tau0 Q' + Q - lambda T = 0
    res = model["tau0"] * (yp["q"] - ym["q"]) / (2 * dt) + y["q"] - ex.lam * y["theta"]
    e = np.abs(res[:200]).max() / np.abs(ex.lam[:200] * y["theta"][:200]).max()
    print(f"(2.11)_3 residual of modes 0..199 at t = {t}: {e:.2e} (relative)")
    ok &= e < 1e-5
    # (2.11)_2: c T' + d p' + lambda Q + gamma1 lambda v = 0
    res = (model["c"] * (yp["theta"] - ym["theta"]) + model["d"] * (yp["P"] - ym["P"])) / (2 * dt) \
        + ex.lam * y["q"] + model["gamma1"] * ex.lam * y["v"]
    e = np.abs(res[:200]).max() / np.abs(ex.lam[:200] * y["q"][:200]).max()
    print(f"(2.11)_2 residual of modes 0..199 at t = {t}: {e:.2e} (relative)")
    ok &= e < 1e-5
    # the batched eigen-decomposition against expm on the first 4096 modes
    small = ExactLinear(model, dict(theta0_step=[20, 0.1], p0_step=[20, 0.1]), 4096)
    ya, yb = small.state(0.25), small.state(0.25, use_expm=True)
    e = np.abs(ya - yb).max() / np.abs(yb).max()
    print(f"eigen-decomposition against expm, 4096 modes, t = 0.25: max difference {e:.2e} (relative)"
          f"; {small.by_expm.size} modes by expm")
    ok &= e < 1e-9
    # truncation: the exp2 pulses with K and 4K modes at t = 0.25
    pulses = dict(theta0_step=[20, 0.1], p0_step=[20, 0.1])
    fine = ExactLinear(model, pulses, 2**20)
    ff = fine.fields(0.25)
    for K in (2**16, 2**18):
        c = ExactLinear(model, pulses, K)
        fc = c.fields(0.25)
        parts = []
        for name in FIELDS:
            fine_on_c = np.interp(c.x, fine.x, ff[name])
            d = math.sqrt(np.mean((fc[name] - fine_on_c) ** 2)) / math.sqrt(np.mean(ff[name] ** 2))
            parts.append(f"{name} {d:.1e}")
        print(f"exp2 pulses, t = 0.25: {K} modes against 2^20, relative L2: " + ", ".join(parts))
    return ok


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run", nargs="?", help="rodcontact HDF5 file")
    p.add_argument("--times", default=None, help="comma-separated snapshot times (before contact)")
    p.add_argument("--modes", type=int, default=2**18, help="number of modes K (default 2^18)")
    p.add_argument("--self-check", action="store_true", help="check the module itself")
    a = p.parse_args(argv[1:])
    if a.self_check:
        return 0 if self_check() else 1
    if not a.run:
        p.print_usage(sys.stderr)
        return 2
    times = [float(s) for s in a.times.split(",")] if a.times else None
    try:
        errs = errors_of_run(a.run, times, a.modes)
    except (KeyError, OSError) as exc:
        sys.stderr.write(f"exact_linear.py: {exc}\n")
        return 2
    except ValueError as exc:
        sys.stderr.write(f"exact_linear.py: {exc}\n")
        return 1
    print("t " + " ".join(FIELDS) + "   (relative L2 error against the exact solution)")
    for t, e in errs.items():
        print(f"{t:g} " + " ".join(f"{e[n]:.4g}" for n in FIELDS))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
