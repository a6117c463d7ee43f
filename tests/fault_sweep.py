#!/usr/bin/env python3
"""Fault-injection sweep: fail each native allocation and submission site of a workload in turn.

For each workload (one conformance case, and `fe render` of every technique), a clean run with
FE_FAULT_TRACE lists every native call it makes, in order ("allocation 17 vkCreateImage"). Then
the workload runs once per target, with FE_FAULT_ALLOC=N or FE_FAULT_SUBMIT=N failing the N-th
call. Targets: the first call of each distinct site (native API call) in the workload, or, with
--every, every call. Each run must end in
  - a clear error: exit 1 naming the out-of-memory result, or a lost device (fe render: exit 4;
    fe conformance: exit 1) saying "device lost"; or
  - a recovered frame: exit 0, the failure handled by the engine;
and never in a crash (a signal), a hang (--timeout), a sanitizer report, or a gdi object still
alive when the device is destroyed (FE_LEAK_CHECK=1). That the device stays usable after an
out-of-memory error is checked in process by NativeFaults (tests/unit/NativeFaultTests.cpp).

Prints one line per failed check and a summary with the sites covered; exit 1 if any check failed.
"""
import argparse
import collections
import os
import re
import subprocess
import sys
import tempfile
import time

OOM = re.compile(r"VK_ERROR_OUT_OF_DEVICE_MEMORY|GL_OUT_OF_MEMORY")
LOST = re.compile(r"device lost", re.IGNORECASE)
SANITIZER = re.compile(r"AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|runtime error:")


def techniques(fe):
    out = subprocess.run([fe, "--help"], capture_output=True, text=True, check=True).stdout
    listed = out.split("techniques (--technique):", 1)[1].splitlines()[1:]
    names = []
    for line in listed:
        m = re.match(r"^  ([a-z][a-z0-9-]+)\s", line)
        if not m:
            break
        names.append(m.group(1))
    return names


def workloads(fe, backend, size, case, only, window):
    out = os.path.join(tempfile.gettempdir(), "fe_fault_sweep_%s%s.png" % (backend, "_window" if window else ""))
    if window:  # the swap chain and the UI: one technique suffices, the others are swept headless
        return [w for w in [
            ("render --window", [fe, "render", "builtin:shadows", "--window", "--backend", backend, "--size", size,
                                 "--frames", "2", "--shadow-map-size", "64", "--out", out]),
            # view's window is at least 64 wide
            ("view", [fe, "view", "builtin:shadows", "--backend", backend, "--size", "96x64", "--frames", "2",
                      "--shadow-map-size", "64", "--screenshot", out]),
        ] if not only or any(o in w[0] for o in only)]
    loads = [("conformance " + case, [fe, "conformance", "--backend", backend, "--case", case])]
    # Shadow maps of 64 texels: the same native calls as the default 1,024 (the sites swept are
    # calls, not sizes), a quarter less time per run.
    for t in techniques(fe):
        loads.append(("render " + t, [fe, "render", "builtin:shadows", "--backend", backend, "--technique", t,
                                      "--size", size, "--frames", "2", "--shadow-map-size", "64",
                                      "--out", out]))
    return [w for w in loads if not only or any(o in w[0] for o in only)]


def run(cmd, env, timeout):
    e = dict(os.environ, FE_LEAK_CHECK="1", **env)
    start = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, env=e, timeout=timeout)
        return p.returncode, p.stdout + p.stderr, time.monotonic() - start
    except subprocess.TimeoutExpired as x:
        out = (x.stdout or b"").decode(errors="replace") + (x.stderr or b"").decode(errors="replace")
        return None, out, time.monotonic() - start


def trace(cmd, timeout):
    with tempfile.NamedTemporaryFile("r", suffix=".trace") as f:
        code, out, _ = run(cmd, {"FE_FAULT_TRACE": f.name}, timeout)
        if code != 0:
            raise SystemExit("clean run failed (exit %s):\n%s\n%s" % (code, " ".join(cmd), out))
        calls = []  # (site, ordinal, API call, the object it is made for or "")
        for line in f:
            site, ordinal, rest = line.split(maxsplit=2)
            name, _, obj = rest.strip().partition(" @")  # "vkCreateImage @scene texture 3"
            calls.append((site, int(ordinal), name, obj))
        return calls


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fe", required=True)
    ap.add_argument("--backend", required=True)
    ap.add_argument("--size", default="32x24")
    ap.add_argument("--case", default="render_to_texture_then_sample", help="the conformance case")
    ap.add_argument("--only", action="append", help="workloads whose name contains this (repeatable)")
    ap.add_argument("--every", action="store_true", help="fail every native call, not each site's first")
    ap.add_argument("--every-workload", action="store_true",
                    help="inject in each workload, also where an earlier one failed the same call after the same calls")
    ap.add_argument("--timeout", type=float, default=120)
    ap.add_argument("--window", action="store_true",
                    help="the windowed backend (vulkan-glfw, gl-glfw; needs a display): render --window and view")
    a = ap.parse_args()

    failures = []
    sites = collections.Counter()  # (kind, call) -> injections
    outcomes = collections.Counter()
    injections = 0
    calls_seen = 0
    began = time.monotonic()
    # The native calls before and at each injection already made, as one prefix of a trace: a
    # workload whose trace begins with the same calls, for the same objects (by debug name),
    # fails at the same point of the same run so far (opening the device, uploading the scene:
    # what every technique's `fe render` shares), and is not run again (--every-workload does).
    # Calls for an object of another name (a technique's own target or pipeline) are injected.
    injected_prefixes = set()
    shared = 0
    for name, cmd in workloads(a.fe, a.backend, a.size, a.case, a.only, a.window):
        calls = trace(cmd, a.timeout)
        calls_seen += len(calls)
        if a.every:
            targets = calls
        else:
            first = {}
            for site, ordinal, call, obj in calls:
                first.setdefault((site, call), (site, ordinal, call, obj))
            targets = list(first.values())
        index = {(site, ordinal): i for i, (site, ordinal, _, _) in enumerate(calls)}
        for site, ordinal, call, obj in targets:
            prefix = tuple((s, c, o) for s, _, c, o in calls[:index[(site, ordinal)] + 1])
            if not a.every_workload and prefix in injected_prefixes:
                shared += 1
                continue
            injected_prefixes.add(prefix)
            var = "FE_FAULT_ALLOC" if site == "allocation" else "FE_FAULT_SUBMIT"
            code, out, secs = run(cmd, {var: str(ordinal)}, a.timeout)
            injections += 1
            sites[(site, call)] += 1
            what = "%s: %s %d (%s)" % (name, site, ordinal, call)
            problems = []
            if code is None:
                problems.append("hang: no exit within %.0f s" % a.timeout)
            elif code < 0:
                problems.append("crash: signal %d" % -code)
            if "fault injection: native %s %d (%s) fails" % (site, ordinal, call) not in out:
                problems.append("the failure was not injected (the workload no longer makes this call?)")
            if SANITIZER.search(out):
                problems.append("sanitizer report")
            if "fe leak check:" in out:
                problems.append("objects left alive: " + out.split("fe leak check:", 1)[1].splitlines()[0].strip())
            if code is not None and code > 0:
                lost = site == "submission"
                expected = {4} if (lost and not name.startswith("conformance")) else {1}
                if code not in expected:
                    problems.append("exit %d, expected %s" % (code, " or ".join(map(str, sorted(expected)))))
                if not (LOST if lost else OOM).search(out):
                    problems.append("the error does not say " + ("the device was lost" if lost else "out of memory"))
                if not lost and LOST.search(out):
                    problems.append("out of memory reported as a lost device")
                outcomes["lost device" if lost else "out-of-memory error"] += 1
            elif code == 0:
                outcomes["recovered"] += 1
            if problems:
                failures.append(what + ": " + "; ".join(problems) + "\n    " + " ".join(cmd) + "\n    "
                                + "\n    ".join(out.strip().splitlines()[-6:]))

    for f in failures:
        print("FAIL " + f)
    kinds = collections.Counter(k for k, _ in sites)
    print("%s%s: %d injections over %d distinct native sites (%d allocation, %d submission) in %d workloads "
          "(%d native calls in their clean runs), %.0f s" %
          (a.backend, " (window)" if a.window else "", injections, len(sites), kinds["allocation"], kinds["submission"],
           len(workloads(a.fe, a.backend, a.size, a.case, a.only, a.window)), calls_seen, time.monotonic() - began))
    print("  %d injections left out: an earlier workload failed the same call after the same calls" % shared)
    print("  outcomes: " + ", ".join("%d %s" % (n, k) for k, n in sorted(outcomes.items())) +
          "; %d crashes, hangs, leaks or unclear errors" % len(failures))
    print("  sites: " + ", ".join("%s (%d)" % (c, n) for (_, c), n in sorted(sites.items())))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
