"""Blender reads a posed skinned character written by `primo deform` as an armature that holds
the posed shape.

Poses assets/meshes/huesitos.fbx (its 9-bone skin) with assets/scenarios/huesitos-raise.json
into raised.glb and raised.obj, imports raised.glb into Blender headless (skinned_glb_check.py)
and checks that the mesh has an armature with the character's bones, that it is skinned by it,
and that the evaluated mesh at rest is the posed OBJ. Blender is $PRIMO_BLENDER, else `blender`
on PATH; without it the script exits 77 (ctest's skip).

Usage: skinned_export_in_blender.py PRIMO_EXECUTABLE
"""

import os
import shutil
import subprocess
import sys
import tempfile

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
BONES = 9


def main():
    primo = sys.argv[1]
    blender = os.environ.get("PRIMO_BLENDER") or shutil.which("blender")
    if not blender:
        print("SKIP: blender not found (Debian package blender; scripts/setup.sh installs it)")
        return SKIP
    scenario = os.path.join(SOURCE, "assets", "scenarios", "huesitos-raise.json")
    with tempfile.TemporaryDirectory() as folder:
        glb, obj = os.path.join(folder, "raised.glb"), os.path.join(folder, "raised.obj")
        for output in (glb, obj):
            subprocess.run([primo, "deform", scenario, "-o", output], check=True)
        check = os.path.join(HERE, "skinned_glb_check.py")
        result = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1",
                                 "--python", check, "--", glb, obj, str(BONES)],
                                capture_output=True, text=True)
        print(result.stdout[-4000:], result.stderr[-4000:])
        return result.returncode


if __name__ == "__main__":
    sys.exit(main())
