"""The Python peers of the work-precision benchmark (benches/work_precision.rs): REBOUND's IAS15 and
WHFast and scipy's DOP853 on the same problems, errors measured the same way. Outside CI; run with

    python3 -m venv /tmp/peers && /tmp/peers/bin/pip install rebound scipy numpy
    /tmp/peers/bin/python benches/peers.py            # or: ... peers.py kepler | solar

Every time is the minimum over interleaved repetitions (the machine is shared: interference only adds
time). Results and versions go to docs/benchmarks.md beside noether's.
"""

import sys
import time

import numpy as np
import rebound
import scipy
from scipy.integrate import solve_ivp

E = 0.6
ORBITS = 100


def best_of(reps, run):
    """Minimum time in ms over `reps` runs of `run`, and its last result."""
    best, out = float("inf"), None
    for _ in range(reps):
        t0 = time.perf_counter()
        out = run()
        best = min(best, (time.perf_counter() - t0) * 1e3)
    return best, out


# ---- Kepler e = 0.6, mu = 1, 100 orbits, error |q(200 pi) - q0| ----

def kepler_start():
    return (1.0 - E, 0.0), (0.0, np.sqrt((1.0 + E) / (1.0 - E)))


def kepler_rebound(integrator, param):
    sim = rebound.Simulation()
    sim.G = 1.0
    sim.add(m=1.0)
    (x, y), (vx, vy) = kepler_start()
    sim.add(m=0.0, x=x, y=y, vx=vx, vy=vy)
    sim.integrator = integrator
    if integrator == "ias15":
        sim.ri_ias15.epsilon = param
    t_end = 2 * np.pi * ORBITS

    def run():
        s = sim.copy()
        s.integrate(t_end)  # exact_finish_time = 1: IAS15 lands on t_end
        p = s.particles[1]
        return np.hypot(p.x - x, p.y - y)

    return run


def kepler_scipy(tol):
    (x, y), (vx, vy) = kepler_start()

    def rhs(_t, u):
        r3 = (u[0] ** 2 + u[1] ** 2) ** 1.5
        return [u[2], u[3], -u[0] / r3, -u[1] / r3]

    def run():
        s = solve_ivp(rhs, (0, 2 * np.pi * ORBITS), [x, y, vx, vy], method="DOP853", rtol=tol, atol=tol)
        return np.hypot(s.y[0, -1] - x, s.y[1, -1] - y)

    return run


# ---- The outer solar system (Hairer-Lubich-Wanner, GNI I.2.4), 200 000 days ----

G_SOLAR = 2.95912208286e-4
SOLAR_T = 200_000.0
# Masses relative to the Sun (the Sun's includes the inner planets), positions in AU and velocities in
# AU/day on 5 September 1994 (GNI, Table I.2.1); the Sun at rest at the origin.
SOLAR = [
    (1.00000597682, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
    (0.000954786104043, (-3.5023653, -3.8169847, -1.5507963), (0.00565429, -0.00412490, -0.00190589)),
    (0.000285583733151, (9.0755314, -3.0458353, -1.6483708), (0.00168318, 0.00483525, 0.00192462)),
    (0.0000437273164546, (8.3101420, -16.2901086, -7.2521278), (0.00354178, 0.00137102, 0.00055029)),
    (0.0000517759138449, (11.4707666, -25.7294829, -10.8169456), (0.00288930, 0.00114527, 0.00039677)),
    (1.0 / 1.3e8, (-15.5387357, -25.2225594, -3.1902382), (0.00276725, -0.00170702, -0.00136504)),
]


def solar_sim():
    sim = rebound.Simulation()
    sim.G = G_SOLAR
    for m, (x, y, z), (vx, vy, vz) in SOLAR:
        sim.add(m=m, x=x, y=y, z=z, vx=vx, vy=vy, vz=vz)
    return sim


def positions(sim):
    return np.array([[p.x, p.y, p.z] for p in sim.particles])


def solar_reference():
    """IAS15 at epsilon 1e-11 (its error is at rounding level long before that)."""
    sim = solar_sim()
    sim.integrator = "ias15"
    sim.ri_ias15.epsilon = 1e-11
    sim.integrate(SOLAR_T)
    return positions(sim)


def solar_error(sim, ref):
    return np.max(np.linalg.norm(positions(sim) - ref, axis=1))


def solar_ias15(eps, ref):
    def run():
        sim = solar_sim()
        sim.integrator = "ias15"
        sim.ri_ias15.epsilon = eps
        sim.integrate(SOLAR_T)
        return solar_error(sim, ref)

    return run


def solar_whfast(steps, ref, corrector=11):
    def run():
        sim = solar_sim()
        sim.integrator = "whfast"
        sim.dt = SOLAR_T / steps
        sim.ri_whfast.corrector = corrector
        sim.ri_whfast.safe_mode = 0
        # Stop after exactly `steps` steps (t = steps·dt to rounding), then synchronize.
        sim.integrate(SOLAR_T - 0.5 * sim.dt, exact_finish_time=0)
        sim.synchronize()
        return solar_error(sim, ref)

    return run


def table(title, param, values, make, reps=5):
    print(f"\n{title}\n| {param} | error | time |\n|---|---|---|")
    points = []
    for v in values:
        ms, err = best_of(reps, make(v))
        print(f"| {v:g} | {err:.2e} | {ms:.3f} ms |")
        points.append((ms, err))
    return points


def time_to(points, target):
    ok = [ms for ms, err in points if err <= target]
    return f"{min(ok):.3f} ms" if ok else "not reached"


def main():
    which = sys.argv[1] if len(sys.argv) > 1 else None
    print(f"rebound {rebound.__version__}, scipy {scipy.__version__}, numpy {np.__version__}")
    summary = []
    if which in (None, "kepler"):
        print("\nKepler e = 0.6, 100 orbits, error |q(200 pi) - q0|")
        pts = table("REBOUND IAS15", "epsilon", [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-9],
                    lambda e: kepler_rebound("ias15", e))
        summary.append(("Kepler", "REBOUND IAS15", pts))
        pts = table("scipy solve_ivp DOP853", "tol", [1e-6, 1e-8, 1e-10, 1e-12, 1e-13],
                    kepler_scipy, reps=3)
        summary.append(("Kepler", "scipy DOP853", pts))
    if which in (None, "solar"):
        ref = solar_reference()
        print("\nOuter solar system, 200 000 days, error max_i |q_i - q_i,ref| in AU "
              "(reference: IAS15 at epsilon 1e-11)")
        print("reference positions (AU):")
        for row in ref:
            print("  " + " ".join(f"{x:+.15e}" for x in row))
        pts = table("REBOUND IAS15", "epsilon", [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
                    lambda e: solar_ias15(e, ref))
        summary.append(("solar", "REBOUND IAS15", pts))
        pts = table("REBOUND WHFast, order-11 correctors", "steps",
                    [2000, 2100, 2500, 3000, 4000, 8000, 16000, 32000, 64000, 128000],
                    lambda n: solar_whfast(n, ref))
        summary.append(("solar", "REBOUND WHFast (corrector 11)", pts))
    print("\n| problem | peer | to 1e-6 | to 1e-10 |\n|---|---|---|---|")
    for problem, name, pts in summary:
        print(f"| {problem} | {name} | {time_to(pts, 1e-6)} | {time_to(pts, 1e-10)} |")


if __name__ == "__main__":
    main()
