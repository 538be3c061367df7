#!/usr/bin/env python3
"""The cost of load histories (issue 43), guarded in CTest (perf.historyCounts.stayWithinBaselineBand).

Three measurements, from `tribos --summary` (default solver parameters, 2 threads):
  - cycle: the paper's bricks (input/two_bricks.xml) in a 20-step cycle (load_end 0 -> 1 -> -1 -> 1 in
    steps of 0.25, load_top held): PFP applications per step, cutbacks, coarse factorisations;
  - bolt: input/bolted_joint.xml (pretension, grip switched on, pull through slip into bearing, 31 steps):
    the same per step, and its pairing changes;
  - memory: the bricks at H/h 8 (2 754 nodes) with --output in 4, 16 and 48 steps: rank 0's peak resident
    memory, which must not grow with the steps (before issue 43 it grew 2.4 MB per step).
The guard is two-sided, as Table 1's (perf/baselines/table1_counts.json): each history's PFP total within
+- band.pfp_relative of the baseline, its outer iterations within +- band.outer_relative, cutbacks and coarse
factorisations equal; the memory's growth from 4 to 48 steps at most band.memory_growth_kb. A count below the
band fails too: write the new baseline (--write-baseline) in a commit that says why.

Usage: history_counts.py TRIBOS SOURCE_DIR BASELINE [--write-baseline]
"""
import json
import os
import subprocess
import sys
import tempfile

CYCLE = "0.25, 0.5, 0.75, 1, 0.75, 0.5, 0.25, 0, -0.25, -0.5, -0.75, -1, -0.75, -0.5, -0.25, 0, 0.25, 0.5, 0.75, 1"
HELD = ", ".join(["1"] * 20)


def run(tribos, source, work, args, output=False):
    """The summary of one run (exit status checked: every history here must converge)."""
    summary = os.path.join(work, "s.json")
    command = [tribos, "--set", "Solver/Verbose=false", "--summary", summary] + args
    if output:
        command += ["--output", os.path.join(work, "r.exo")]
    env = dict(os.environ, OMP_NUM_THREADS="2")
    done = subprocess.run(command, cwd=source, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.exit("FAILED: %s: exit %d\n%s" % (" ".join(args), done.returncode, done.stdout[-3000:]))
    return json.load(open(summary))


def history(summary):
    steps = summary["steps"]
    return {
        "steps": len(steps),
        "pfp": summary["pfp_applications"],
        "outer": summary["outer_iterations"],
        "pfp_per_step": [k["pfp_applications"] for k in steps],
        "cutbacks": sum(k.get("cutbacks", 0) for k in steps),
        "coarse_factorizations": summary["operator_profile"]["coarse_factorizations"],
    }


def measure(tribos, source, work):
    cycle = run(tribos, source, work, ["--input", "input/two_bricks.xml", "--set", "Load Steps/Number Of Steps=20",
                                      "--set", "Load Steps/load_end/Factors={%s}" % CYCLE,
                                      "--set", "Load Steps/load_top/Factors={%s}" % HELD])
    bolt = run(tribos, source, work, ["--input", "input/bolted_joint.xml"])
    memory = {}
    for n in (4, 16, 48):
        s = run(tribos, source, work, ["--input", "input/two_bricks.xml", "--set", "Mesh/H Over h=8",
                                       "--set", "Load Steps/Number Of Steps=%d" % n], output=True)
        memory[str(n)] = s["max_rss_per_rank_kb"][0]
    out = {"cycle": history(cycle), "bolt": history(bolt), "rank0_peak_kb_by_steps": memory}
    out["bolt"]["pairing_changes"] = len(bolt.get("pairing_updates", []))
    return out


def within(name, value, base, relative, bad):
    low, high = base * (1 - relative), base * (1 + relative)
    ok = low <= value <= high
    print("%s %s: %s (baseline %s, band [%.0f, %.0f])" % ("ok" if ok else "FAILED", name, value, base, low, high))
    if not ok:
        bad.append(name)


def equal(name, value, base, bad):
    print("%s %s: %s (baseline %s)" % ("ok" if value == base else "FAILED", name, value, base))
    if value != base:
        bad.append(name)


def guard(now, baseline):
    band, bad = baseline["band"], []
    for scene in ("cycle", "bolt"):
        within(scene + " PFP", now[scene]["pfp"], baseline[scene]["pfp"], band["pfp_relative"], bad)
        within(scene + " outer", now[scene]["outer"], baseline[scene]["outer"], band["outer_relative"], bad)
        equal(scene + " steps", now[scene]["steps"], baseline[scene]["steps"], bad)
        equal(scene + " cutbacks", now[scene]["cutbacks"], baseline[scene]["cutbacks"], bad)
        equal(scene + " coarse factorisations", now[scene]["coarse_factorizations"],
              baseline[scene]["coarse_factorizations"], bad)
    memory = now["rank0_peak_kb_by_steps"]
    growth = memory["48"] - memory["4"]
    ok = growth <= band["memory_growth_kb"]
    print("%s rank 0's peak memory 4 / 16 / 48 steps: %s KiB (growth %d KiB, at most %d)" %
          ("ok" if ok else "FAILED", " / ".join(str(memory[k]) for k in ("4", "16", "48")), growth,
           band["memory_growth_kb"]))
    if not ok:
        bad.append("memory growth")
    return bad


def main():
    tribos, source, baseline_path = sys.argv[1:4]
    with tempfile.TemporaryDirectory() as work:
        now = measure(os.path.abspath(tribos), os.path.abspath(source), work)
    print(json.dumps(now))
    if "--write-baseline" in sys.argv[4:]:
        old = json.load(open(baseline_path)) if os.path.exists(baseline_path) else {}
        now["_comment"] = old.get("_comment", "perf/history_counts.py")
        now["band"] = old.get("band", {"pfp_relative": 0.1, "outer_relative": 0.1, "memory_growth_kb": 8000})
        json.dump(now, open(baseline_path, "w"), indent=1)
        print("wrote", baseline_path)
        return
    bad = guard(now, json.load(open(baseline_path)))
    if bad:
        sys.exit("FAILED: " + ", ".join(bad) + " (a count below the band: write the new baseline with "
                 "--write-baseline in a commit that says why)")


if __name__ == "__main__":
    main()
