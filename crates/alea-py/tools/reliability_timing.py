"""Per-call cost of a Python model in alea's rare-event methods, and the same analysis on a
chaos evaluated in Rust (linear limit state in 4 standard normals, pf = 1e-5)."""
import time
import alea

BETA = 4.264890793922602
law = [alea.Normal(0.0, 1.0)] * 4
g = lambda x: BETA - (x[:, 0] + x[:, 1] - x[:, 2] + x[:, 3]) / 2.0  # noqa: E731
x = alea.lhs(law, 40, seed=1)
pc = alea.PolynomialChaos.regression(law, 1, x, (x[:, 0] + x[:, 1] - x[:, 2] + x[:, 3]) / 2.0)
for name, f, kw in [("subset", alea.subset_simulation, {}), ("importance", alea.importance_sampling, {})]:
    for label, model, extra in [("python", g, {}), ("chaos", pc, {"threshold": BETA})]:
        best = float("inf")
        for _ in range(3):
            t = time.perf_counter()
            r = f(model, law, **extra, **kw)
            best = min(best, time.perf_counter() - t)
        print(f"{name:10s} {label:6s} pf {r.pf:.3e} [{r.interval[0]:.3e}, {r.interval[1]:.3e}] calls {r.calls:6d} "
              f"{best * 1e3:7.1f} ms  {best / r.calls * 1e6:6.2f} us/call")
