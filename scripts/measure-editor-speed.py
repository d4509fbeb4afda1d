#!/usr/bin/env python3
"""The editor's speed as a user sees it, on this machine, in one command.

Opens each mesh in the real editor window under Xvfb (software OpenGL: Mesa's llvmpipe),
with its bottom tenth fixed and its top tenth a position handle, waits until it has settled,
drags the handle with the mouse for a few seconds through the editor's input queue (a
`--script`, the path real mouse events take), lets go and waits until it settles again.
Prints per run and per mesh: frames a second while dragging (and of them drawn: those that
showed a new picture), mesh updates (changed positions shown) a second, ms per frame (median,
90th percentile), the solver's ms per iteration, seconds to settle after the release, and the
load average (1 min) before and during the run.

    scripts/measure-editor-speed.py                  # spot, armadillo, bunny-238k; 3 runs each
    scripts/measure-editor-speed.py --meshes koala --runs 5 --primo build/src/primo

Meshes: spot (assets/), armadillo (29k faces), koala (100k) and bunny-238k (bunny_hr
Loop-subdivided once, 238,656 faces, made with `primo generate loop` on first use) from the
shared test meshes (--shared-meshes; a mesh that is not there is skipped with a message).
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# name -> (file, where: "assets" or "shared", Loop steps)
MESHES = {
    "spot": ("meshes/spot_quadrangulated.obj", "assets", 0),
    "armadillo": ("armadillo_29k.obj", "shared", 0),
    "koala": ("koala.obj", "shared", 0),
    "bunny-238k": ("bunny_hr.obj", "shared", 1),
}

GESTURE = re.compile(
    r"drag '(?P<handle>[^']*)': (?P<frames>\d+) frames, (?P<mean>[\d.]+) ms mean, "
    r"(?P<max>[\d.]+) ms max per frame; solver (?P<iteration>[\d.]+) ms per iteration; "
    r"the mesh changed (?P<updates>\d+) times \((?P<updates_per_second>[\d.]+) a second, "
    r"(?P<previews>\d+) of them previews\)"
    r"(?:; (?P<fps>[\d.]+) frames a second, (?P<median>[\d.]+) ms median and "
    r"(?P<p90>[\d.]+) ms 90th percentile per frame, (?P<drawn>\d+) drawn "
    r"\((?P<drawn_per_second>[\d.]+) a second\))?")


def find_shared_meshes():
    folder = ROOT
    while True:
        candidate = os.path.join(folder, "shared", "meshes")
        if os.path.isdir(candidate):
            return candidate
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent


def load_average():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def bounding_box(path):
    """The mesh file's vertex bounds (OBJ `v` lines or OFF vertices)."""
    lo, hi = [float("inf")] * 3, [float("-inf")] * 3

    def take(xyz):
        for i in range(3):
            lo[i], hi[i] = min(lo[i], xyz[i]), max(hi[i], xyz[i])

    with open(path) as f:
        if path.lower().endswith(".off"):
            words = f.read().split()
            n = int(words[1])
            for v in range(n):
                take([float(w) for w in words[4 + 3 * v: 7 + 3 * v]])
        else:
            for line in f:
                if line.startswith("v "):
                    take([float(w) for w in line.split()[1:4]])
    if lo[0] == float("inf"):
        sys.exit(f"measure-editor-speed: {path}: no vertices found")
    return lo, hi


def write_scenario(folder, mesh, name):
    lo, hi = bounding_box(mesh)
    span = hi[1] - lo[1]
    pad = [0.01 * (hi[i] - lo[i]) + 1e-9 for i in range(3)]
    below = [lo[i] - pad[i] for i in range(3)]
    above = [hi[i] + pad[i] for i in range(3)]
    path = os.path.join(folder, f"{name}.json")
    with open(path, "w") as f:
        f.write(f"""{{
  "format": "primo-scenario/1",
  "mesh": "{os.path.abspath(mesh)}",
  "handles": [
    {{ "name": "bottom", "select": {{ "box": {{ "min": {below}, "max": [{above[0]}, {lo[1] + 0.1 * span}, {above[2]}] }} }}, "fix": "all" }},
    {{ "name": "top", "select": {{ "box": {{ "min": [{below[0]}, {hi[1] - 0.1 * span}, {below[2]}], "max": {above} }} }}, "fix": "position" }}
  ]
}}
""")
    return path


def write_script(folder, seconds):
    path = os.path.join(folder, "drag.txt")
    with open(path, "w") as f:
        # The wait after the first settle lets the stand-in of a big mesh be built, as a user
        # looks at the mesh before dragging it.
        f.write(f"""wait-settled 300
wait 2
move @top
wait 0.3
press left
move @top 150 0 over {seconds}
release left
echo measure: released
wait-settled 300
echo measure: settled
quit
""")
    return path


def run_once(primo, scenario, script, timeout):
    command = ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", primo, "edit", scenario,
               "--script", script, "--timeout", str(timeout)]
    samples, stop = [], threading.Event()

    def sample_load():
        while not stop.wait(1.0):
            samples.append(load_average())

    before = load_average()
    sampler = threading.Thread(target=sample_load, daemon=True)
    sampler.start()
    released = settled = None
    gesture = None
    log = []
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True, bufsize=1)
    for line in process.stdout:
        now = time.monotonic()
        log.append(line)
        if gesture is None and (m := GESTURE.search(line)):
            gesture = m
        elif "measure: released" in line:
            released = now
        elif "measure: settled" in line:
            settled = now
    code = process.wait()
    stop.set()
    sampler.join()
    if code != 0 or gesture is None or released is None or settled is None:
        sys.stderr.write("".join(log))
        sys.exit(f"measure-editor-speed: the editor run on {scenario} failed (exit status {code})")
    g = {k: (float(v) if v is not None else None) for k, v in gesture.groupdict().items()
         if k != "handle"}
    seconds = g["frames"] * g["mean"] / 1000.0
    return {
        "fps": g["fps"] if g["fps"] is not None else g["frames"] / seconds,
        "drawn": g["drawn_per_second"],
        "updates": g["updates_per_second"],
        "median": g["median"],
        "p90": g["p90"],
        "iteration": g["iteration"],
        "settle": settled - released,
        "load_before": before,
        "load_during": statistics.mean(samples) if samples else before,
    }


def shown(value, digits=1):
    return "n/a" if value is None else f"{value:.{digits}f}"


def span(values, digits=1):
    values = [v for v in values if v is not None]
    if not values:
        return "n/a"
    lo, hi = min(values), max(values)
    return shown(lo, digits) if f"{lo:.{digits}f}" == f"{hi:.{digits}f}" else \
        f"{lo:.{digits}f}-{hi:.{digits}f}"


COLUMNS = [("fps", "frames/s", 1), ("drawn", "drawn/s", 1), ("updates", "mesh updates/s", 1), ("median", "ms/frame median", 0),
           ("p90", "ms/frame p90", 0), ("iteration", "ms/iteration", 0), ("settle", "settle s", 2),
           ("load_before", "load before", 1), ("load_during", "load during", 1)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshes", default="spot,armadillo,bunny-238k",
                        help=f"comma-separated, of: {', '.join(MESHES)}")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=4.0, help="how long the drag lasts")
    parser.add_argument("--primo", default=os.path.join(ROOT, "build", "src", "primo"))
    parser.add_argument("--shared-meshes", default=find_shared_meshes(),
                        help="the shared test meshes' folder (default: shared/meshes above here)")
    parser.add_argument("--work", help="folder for the scenarios and generated meshes")
    parser.add_argument("--timeout", type=float, default=600.0, help="per editor run, seconds")
    args = parser.parse_args()
    names = args.meshes.split(",")
    unknown = [n for n in names if n not in MESHES]
    if unknown:
        sys.exit(f"measure-editor-speed: unknown mesh '{unknown[0]}' (known: {', '.join(MESHES)})")
    if args.runs < 1 or not 0 < args.seconds <= 600:
        sys.exit("measure-editor-speed: --runs must be at least 1 and --seconds in (0, 600]")
    if not os.access(args.primo, os.X_OK):
        sys.exit(f"measure-editor-speed: {args.primo}: no primo executable (build it first)")
    work = args.work or tempfile.mkdtemp(prefix="primo-speed-")
    os.makedirs(work, exist_ok=True)
    script = write_script(work, args.seconds)

    # Xvfb has no GPU: the editor draws with Mesa's llvmpipe on the same cores as the solver.
    print(f"# {time.strftime('%Y-%m-%d %H:%M')}, {os.cpu_count()} cores, Xvfb (llvmpipe), "
          f"{args.seconds:g} s drag of the top tenth (bottom tenth fixed), {args.runs} runs")
    results = {}
    for name in names:
        file, where, steps = MESHES[name]
        folder = os.path.join(ROOT, "assets") if where == "assets" else args.shared_meshes
        source = os.path.join(folder, file) if folder else None
        if not source or not os.path.isfile(source):
            print(f"# {name}: skipped, {source or 'shared/meshes'} is not there "
                  "(give the shared test meshes' folder with --shared-meshes)")
            continue
        mesh = source
        if steps:
            mesh = os.path.join(work, f"{name}.obj")
            if not os.path.isfile(mesh):
                subprocess.run([args.primo, "generate", "loop", source, "--steps", str(steps),
                                "-o", mesh], check=True, stdout=subprocess.DEVNULL)
        scenario = write_scenario(work, mesh, name)
        runs = []
        for r in range(args.runs):
            m = run_once(args.primo, scenario, script, args.timeout)
            runs.append(m)
            print(f"{name} run {r + 1}: " +
                  ", ".join(f"{label} {shown(m[key], d)}" for key, label, d in COLUMNS), flush=True)
        results[name] = runs

    print("\n| mesh | " + " | ".join(label for _, label, _ in COLUMNS) + " |")
    print("|---|" + "---:|" * len(COLUMNS))
    for name, runs in results.items():
        print(f"| {name} | " + " | ".join(span([m[key] for m in runs], d) for key, _, d in COLUMNS)
              + " |")


if __name__ == "__main__":
    main()
