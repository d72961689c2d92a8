"""The peer benchmark: the Robotics Toolbox for Python's C++ Levenberg-Marquardt IK
(`ETS.ik_LM`) beside ArmLab's `ikbench`, on the same protocol and the same targets.

Protocol (as crates/armlab-bench/src/ik.rs): random joint vectors within the UR10's limits drawn with
ikbench's SplitMix64 and seed (so both solve exactly the same targets), target = FK(q),
a full-pose solve from the same seed point (the midpoint of the limits: q = 0), success =
position error <= 1e-5 m and orientation error <= 1e-5 rad, checked by an FK written here
from the DH table (not RTB's own fkine). RTB's UR10 is built here from the modified DH
table of docs/SPEC (the numbers are checked against assets/robots/ur10.json and against
the pose at q = 0), not taken from RTB's model zoo.

Rounds alternate the two (RTB in this process, then ikbench in a child process) so that
both see the same machine load; the report gives each round and the medians over rounds.

Run through tools/peers/run.sh, which creates the virtual environment and builds ikbench.
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np
import roboticstoolbox as rtb

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# SPEC §1.2, modified DH (Craig): (alpha_{i-1} in degrees, a_{i-1} in m, d_i in m).
UR10_MDH = [
    (0.0, 0.0, 0.128),
    (90.0, 0.0, 0.0),
    (0.0, 0.6129, 0.0),
    (0.0, 0.5716, 0.1639),
    (-90.0, 0.0, 0.1157),
    (90.0, 0.0, 0.0922),
]
SUCCESS_TOLERANCE = 1e-5  # m and rad, as ikbench
IKBENCH_SEED = 20_240_601  # BenchConfig::default().seed in crates/armlab-bench/src/ik.rs


class SplitMix64:
    """crates/armlab-core/src/rng.rs, bit for bit: the same joint vectors as ikbench."""

    MASK = (1 << 64) - 1

    def __init__(self, seed):
        self.state = seed & self.MASK

    def next_u64(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & self.MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & self.MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & self.MASK
        return z ^ (z >> 31)

    def uniform(self, lo, hi):
        return lo + (hi - lo) * ((self.next_u64() >> 11) * (1.0 / (1 << 53)))


def armlab_ur10():
    """The UR10 rows and limits (radians) from ArmLab's robot file, checked against SPEC."""
    with open(os.path.join(ROOT, "assets", "robots", "ur10.json"), encoding="utf-8") as f:
        robot = json.load(f)
    if robot.get("convention") != "modified" or robot.get("length_unit") != "mm":
        raise SystemExit("assets/robots/ur10.json is no longer modified DH in mm")
    limits = []
    for (alpha, a, d), joint in zip(UR10_MDH, robot["joints"], strict=True):
        same = (
            joint["type"] == "revolute"
            and joint["theta_deg"] == 0
            and joint["alpha_deg"] == alpha
            and math.isclose(joint["a"] / 1000.0, a, abs_tol=1e-12)
            and math.isclose(joint["d"] / 1000.0, d, abs_tol=1e-12)
        )
        if not same:
            raise SystemExit(f"ur10.json differs from SPEC's table: {joint}")
        # f64::to_radians in Rust is x * (π/180), as math.radians.
        limits.append((math.radians(joint["min_deg"]), math.radians(joint["max_deg"])))
    return limits


def fk_mdh(q):
    """Tool pose of the UR10 at q, from the modified DH matrices of SPEC §2 (4x4, m)."""
    t = np.eye(4)
    for (alpha_deg, a, d), theta in zip(UR10_MDH, q):
        al = math.radians(alpha_deg)
        ca, sa, ct, st = math.cos(al), math.sin(al), math.cos(theta), math.sin(theta)
        link = np.array(
            [
                [ct, -st, 0.0, a],
                [st * ca, ct * ca, -sa, -sa * d],
                [st * sa, ct * sa, ca, ca * d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
        t = t @ link
    return t


def pose_errors(t, target):
    """Position error (m) and rotation angle of target·tᵀ (rad)."""
    pe = float(np.linalg.norm(target[:3, 3] - t[:3, 3]))
    r = target[:3, :3] @ t[:3, :3].T
    c = max(-1.0, min(1.0, 0.5 * (np.trace(r) - 1.0)))
    s = 0.5 * math.sqrt(
        (r[2, 1] - r[1, 2]) ** 2 + (r[0, 2] - r[2, 0]) ** 2 + (r[1, 0] - r[0, 1]) ** 2
    )
    return pe, math.atan2(s, c)


def rtb_ur10(limits):
    links = [
        rtb.RevoluteMDH(alpha=math.radians(alpha), a=a, d=d, qlim=[lo, hi])
        for (alpha, a, d), (lo, hi) in zip(UR10_MDH, limits)
    ]
    return rtb.DHRobot(links, name="UR10 (SPEC modified DH)").ets()


def check_models(ets, limits):
    """RTB's chain, this file's FK and SPEC's pose at q = 0 agree (raises otherwise)."""
    t0 = fk_mdh(np.zeros(6))
    spec_p = np.array([1.1845, -0.2561, 0.2437])
    spec_r = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], dtype=float)
    if not (np.allclose(t0[:3, 3], spec_p, atol=1e-9) and np.allclose(t0[:3, :3], spec_r, atol=1e-12)):
        raise SystemExit(f"FK at q = 0 is not SPEC's pose: {t0}")
    rng = SplitMix64(1)
    worst = 0.0
    for _ in range(200):
        q = np.array([rng.uniform(lo, hi) for lo, hi in limits])
        worst = max(worst, float(np.abs(np.asarray(ets.fkine(q).A) - fk_mdh(q)).max()))
    if worst > 1e-12:
        raise SystemExit(f"RTB's chain differs from the DH table by {worst}")
    return worst


def percentile(sorted_values, f):
    """The percentile as crates/armlab-bench/src/stats.rs takes it: the sample at round((n − 1)·f)."""
    if not sorted_values:
        return 0.0
    last = len(sorted_values) - 1
    return sorted_values[min(last, round(last * f))]


def run_rtb(ets, limits, samples, ilimit, slimit, tol):
    rng = SplitMix64(IKBENCH_SEED)
    targets = []
    for _ in range(samples):
        q = [rng.uniform(lo, hi) for lo, hi in limits]
        targets.append(fk_mdh(q))
    seed = np.array([0.5 * (lo + hi) for lo, hi in limits])
    times, iterations, searches, ok = [], [], [], 0
    ik = ets.ik_LM
    clock = time.perf_counter
    for target in targets:
        t0 = clock()
        sol = ik(target, q0=seed, ilimit=ilimit, slimit=slimit, tol=tol, joint_limits=True)
        t1 = clock()
        times.append((t1 - t0) * 1e6)
        iterations.append(sol.iterations)
        searches.append(sol.searches)
        pe, oe = pose_errors(fk_mdh(sol.q), target)
        if pe <= SUCCESS_TOLERANCE and oe <= SUCCESS_TOLERANCE:
            ok += 1
    times.sort()
    return {
        "success_pct": round(100.0 * ok / samples, 4),
        "median_us": round(percentile(times, 0.5), 2),
        "p99_us": round(percentile(times, 0.99), 2),
        "iterations_mean": round(statistics.fmean(iterations), 2),
        "searches_mean": round(statistics.fmean(searches), 3),
    }


def run_armlab(ikbench, samples, budget):
    out = subprocess.run(
        [ikbench, str(samples), str(budget)], check=True, capture_output=True, text=True
    ).stdout
    report = json.loads(out)
    if report["seed"] != IKBENCH_SEED:
        raise SystemExit(f"ikbench's seed is {report['seed']}, this script draws {IKBENCH_SEED}")
    rows = {r["name"]: r for r in report["rows"]}
    picked = {}
    for key, name in [
        ("cold", "ur10 cold, damped least squares alone"),
        ("seed_table", "ur10 cold, seed table"),
    ]:
        row = rows.get(name)
        if row is not None:
            picked[key] = {
                "success_pct": row["success_pct"],
                "median_us": row["time_us"]["median"],
                "p99_us": row["time_us"]["p99"],
                "iterations_mean": row["iterations"]["mean"],
            }
    return picked, report.get("runtime", "")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ikbench", required=True, help="path of the release ikbench binary")
    ap.add_argument("--samples", type=int, default=10_000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--budget", type=int, default=1000, help="ArmLab's iteration budget")
    # RTB: 30 iterations per search (its default), 33 searches: 990 iterations at most,
    # ArmLab's 1000-iteration budget. Its tol bounds E = ½‖e‖² (m, rad): 1.25e-11 is
    # ‖e‖ ≤ 5e-6, ikbench's solver tolerance, below the 1e-5 success test.
    ap.add_argument("--ilimit", type=int, default=30)
    ap.add_argument("--slimit", type=int, default=33)
    ap.add_argument("--tol", type=float, default=1.25e-11)
    args = ap.parse_args()

    limits = armlab_ur10()
    ets = rtb_ur10(limits)
    model_diff = check_models(ets, limits)
    rounds = []
    for _ in range(args.rounds):
        peer = run_rtb(ets, limits, args.samples, args.ilimit, args.slimit, args.tol)
        ours, runtime = run_armlab(args.ikbench, args.samples, args.budget)
        rounds.append({"rtb_ik_LM": peer, "armlab": ours})

    def med(path):
        vals = []
        for r in rounds:
            v = r
            for p in path:
                v = v.get(p) if isinstance(v, dict) else None
            if v is not None:
                vals.append(v)
        return round(statistics.median(vals), 4) if vals else None

    summary = {
        "rtb_ik_LM_median_us": med(["rtb_ik_LM", "median_us"]),
        "rtb_ik_LM_success_pct": med(["rtb_ik_LM", "success_pct"]),
        "armlab_cold_median_us": med(["armlab", "cold", "median_us"]),
        "armlab_cold_success_pct": med(["armlab", "cold", "success_pct"]),
        "ratio_cold": med_ratio(rounds, "cold"),
    }
    if any("seed_table" in r["armlab"] for r in rounds):
        summary["armlab_seed_table_median_us"] = med(["armlab", "seed_table", "median_us"])
        summary["ratio_seed_table"] = med_ratio(rounds, "seed_table")
    print(
        json.dumps(
            {
                "benchmark": "UR10 full-pose IK, ikbench protocol, same targets and same seed (q = 0)",
                "protocol": {
                    "samples": args.samples,
                    "target_seed": IKBENCH_SEED,
                    "success": "1e-5 m and 1e-5 rad by an independent FK",
                    "armlab_budget_iterations": args.budget,
                    "rtb_settings": {
                        "method": "chan",
                        "k": 1.0,
                        "ilimit": args.ilimit,
                        "slimit": args.slimit,
                        "tol": args.tol,
                        "joint_limits": True,
                    },
                    "rtb_timing": "time.perf_counter around each ets.ik_LM call (Python call included)",
                    "armlab_timing": "ikbench (native release), std::time::Instant around each solve",
                },
                "versions": {
                    "roboticstoolbox": rtb.__version__,
                    "numpy": np.__version__,
                    "python": sys.version.split()[0],
                    "armlab_runtime": runtime,
                },
                "model_check_max_diff": model_diff,
                "rounds": rounds,
                "median_over_rounds": summary,
            },
            indent=2,
        )
    )


def med_ratio(rounds, key):
    ratios = [
        r["rtb_ik_LM"]["median_us"] / r["armlab"][key]["median_us"]
        for r in rounds
        if key in r["armlab"] and r["armlab"][key]["median_us"] > 0
    ]
    return round(statistics.median(ratios), 2) if ratios else None


if __name__ == "__main__":
    main()
