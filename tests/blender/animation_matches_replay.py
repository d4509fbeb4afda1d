"""Blender reads `primo replay --animation` as `primo replay --frames` wrote the frames.

Replays a short session on a bar (a drag of its top over ten frames, an idle stretch, one more
pose) with `--every 3 --frames DIR --animation anim.glb`, imports anim.glb into Blender
headless (blender_import_check.py) and compares, at every kept frame's time (computed here from
the session), Blender's
evaluated mesh with DIR/frame_NNNNNN.obj. Blender is $PRIMO_BLENDER, else `blender` on PATH;
without it the script exits 77 (ctest's skip).

Usage: animation_matches_replay.py PRIMO_EXECUTABLE
"""

import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))


def read_obj(path):
    points, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                points.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                faces.append([int(c.split("/")[0]) - 1 for c in parts[1:]])
    return points, faces


def centroid(points, face):
    return [sum(points[v][k] for v in face) / len(face) for k in range(3)]


def handle(name, mode, faces, points, all_faces):
    cs = [centroid(points, all_faces[f]) for f in faces]
    center = [sum(c[k] for c in cs) / len(cs) for k in range(3)]
    return {"name": name, "mode": mode, "faces": faces, "stiffness": 10.0, "center": center,
            "translate": [0, 0, 0], "rotation": [1, 0, 0, 0]}


def session(points, faces):
    ys = [centroid(points, f)[1] for f in faces]
    low, high = min(ys), max(ys)
    span = high - low
    bottom = [i for i, y in enumerate(ys) if y < low + 0.05 * span]
    top = [i for i, y in enumerate(ys) if y > high - 0.05 * span]
    events = []
    # Uneven frame times, as an editor records them.
    for frame in range(1, 11):
        angle = 0.05 * frame
        events.append({"frame": frame, "t": 0.017 * frame + 0.002 * (frame % 3), "type": "targets",
                       "poses": [{"handle": 1, "translate": [0.03 * frame, 0, 0.01 * frame],
                                  "rotation": [math.cos(angle / 2), 0, 0, math.sin(angle / 2)]}]})
    events.append({"frame": 30, "t": 0.9, "type": "targets",
                   "poses": [{"handle": 1, "translate": [0.2, 0.05, 0.1], "rotation": [1, 0, 0, 0]}]})
    return {"format": "primo-session/1", "mesh": "bar.obj",
            "initial": {"prisms": {"height": 1.0, "width": 1.0, "normal_blend": 0.0},
                        "handles": [handle("base", "fixed", bottom, points, faces),
                                    handle("top", "pose", top, points, faces)]},
            "events": events}


def frame_times(events, every):
    """Each kept frame's time: its first event's t, or evenly spaced between the frames that
    have one (frame 0 at 0), as docs/sessions.md says."""
    timed = {0: 0.0}
    for e in events:
        timed.setdefault(e["frame"], e["t"])
    anchors = sorted(timed.items())
    last = anchors[-1][0]
    times = {}
    for frame in range(0, last + 1, every):
        (f0, t0), (f1, t1) = max(a for a in anchors if a[0] <= frame), min(
            (a for a in anchors if a[0] >= frame), default=anchors[-1])
        times["frame_%06d" % frame] = t0 if f1 == f0 else t0 + (t1 - t0) * (frame - f0) / (f1 - f0)
    return times


def main():
    primo = os.path.abspath(sys.argv[1])
    blender = os.environ.get("PRIMO_BLENDER") or shutil.which("blender")
    if not blender:
        print("SKIP: blender is not on PATH (apt-get install blender); the animated glTF was "
              "not checked in Blender")
        return SKIP
    work = tempfile.mkdtemp(prefix="primo-blender-")
    run = lambda *args: subprocess.run(args, check=True, cwd=work)
    run(primo, "generate", "bar", "-o", "bar.obj", "--across", "2", "--along", "8")
    points, faces = read_obj(os.path.join(work, "bar.obj"))
    recorded = session(points, faces)
    with open(os.path.join(work, "bar.session.json"), "w") as f:
        json.dump(recorded, f)
    with open(os.path.join(work, "times.json"), "w") as f:
        json.dump(frame_times(recorded["events"], 3), f)
    run(primo, "replay", "bar.session.json", "-o", "final.obj", "--every", "3", "--frames", "frames",
        "--animation", "anim.glb")
    # Blender's Python takes its standard library from the first python3 on PATH: a pyenv or
    # venv interpreter running this script puts its own folder first, without Debian's NumPy,
    # which Blender's glTF importer needs.
    own = os.path.dirname(sys.executable)
    env = dict(os.environ, PATH=os.pathsep.join(
        p for p in os.environ.get("PATH", "").split(os.pathsep) if p and p != own))
    result = subprocess.run(
        [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
         os.path.join(HERE, "blender_import_check.py"), "--", os.path.join(work, "anim.glb"),
         os.path.join(work, "frames"), os.path.join(work, "bar.obj"), os.path.join(work, "times.json")],
        capture_output=True, text=True, env=env)
    lines = [l for l in result.stdout.splitlines() if l.startswith(("frame", "CHECK", "FAIL"))]
    print("\n".join(lines))
    if result.returncode != 0:
        print(result.stdout[-4000:], result.stderr[-4000:])
        return 1
    shutil.rmtree(work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
