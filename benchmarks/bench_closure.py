"""How many two-contact friction grasps per second each test decides.

Prints, for batches of random grasps, the rate of the batched theorem 6.3 test
(``friction_pair_closure``), of the batched general test (``is_force_closure`` on
the four friction-cone wrenches), and of the LP a user would write (scipy's HiGHS,
one grasp at a time, on a sample), side by side.

    python benchmarks/bench_closure.py [--n N]
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from scipy.optimize import linprog

import fcgrasp as fc
from fcgrasp.core.contacts import friction_cone_edges


def _rate(fn, n, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return n / best, best


def lp_closure(w):
    """Strictly positive combination of the unit wrenches vanishes, and rank 3."""
    v = w / np.linalg.norm(w, axis=1, keepdims=True)
    k = len(v)
    a_eq = np.vstack([np.hstack([v.T, np.zeros((3, 1))]), np.r_[np.ones(k), 0.0]])
    res = linprog(np.r_[np.zeros(k), -1.0], A_ub=np.hstack([-np.eye(k), np.ones((k, 1))]),
                  b_ub=np.zeros(k), A_eq=a_eq, b_eq=np.r_[0.0, 0.0, 0.0, 1.0],
                  bounds=[(0, None)] * k + [(None, None)], method="highs")
    return res.status == 0 and -res.fun > 1e-9 and np.linalg.matrix_rank(v) == 3


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000, help="grasps per batch")
    ap.add_argument("--lp", type=int, default=300, help="grasps for the LP baseline")
    args = ap.parse_args()
    rng = np.random.default_rng(0)
    n = args.n
    p, q = rng.random((2, n, 2))
    np_, nq = rng.normal(size=(2, n, 2))
    np_ /= np.linalg.norm(np_, axis=1, keepdims=True)
    nq /= np.linalg.norm(nq, axis=1, keepdims=True)
    mu = rng.uniform(0.05, 1.0, n)
    pts = np.concatenate([np.repeat(p[:, None], 2, 1), np.repeat(q[:, None], 2, 1)], axis=1)
    w = fc.wrench_from_force(np.concatenate([friction_cone_edges(np_, mu),
                                             friction_cone_edges(nq, mu)], axis=1), pts)

    geo_rate, geo_t = _rate(lambda: fc.friction_pair_closure(p, np_, q, nq, mu), n)
    gen_rate, gen_t = _rate(lambda: fc.is_force_closure(w), n, repeat=1)
    m = min(args.lp, n)
    lp_rate, lp_t = _rate(lambda: [lp_closure(w[i]) for i in range(m)], m, repeat=1)
    agree = np.array_equal(fc.friction_pair_closure(p[:m], np_[:m], q[:m], nq[:m], mu[:m]),
                           np.array([lp_closure(w[i]) for i in range(m)]))

    print(f"two friction contacts, random, batch of {n:,} (LP on {m})")
    print(f"{'method':44s} {'grasps/s':>14s} {'s/batch':>10s} {'vs LP':>10s}")
    rows = [("theorem 6.3, batched (friction_pair_closure)", geo_rate, geo_t),
            ("general test, batched (is_force_closure)", gen_rate, gen_t),
            ("LP per grasp (scipy HiGHS)", lp_rate, lp_t)]
    for name, r, t in rows:
        print(f"{name:44s} {r:14,.0f} {t:10.4f} {r / lp_rate:10.0f}x")
    print(f"theorem 6.3 / general: {geo_rate / gen_rate:.1f}x; LP sample agrees: {agree}")


if __name__ == "__main__":
    main()
