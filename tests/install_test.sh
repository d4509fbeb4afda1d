#!/usr/bin/env bash
# The installed PriMo works on its own: `cmake --install` into a scratch prefix, then the
# installed `primo` solves a shipped scenario, the installed Python module imports, and the
# installed editor renders the bundled Spot with the installed shaders, all from a folder
# outside the source and build trees. The editor needs an X server: without xvfb-run the test
# stops there and reports a skip (exit 77). Before that, with cpack and dpkg-deb, the .deb is
# built too and its contents checked.
#
# usage: install_test.sh BUILD_DIR SOURCE_DIR [PYTHON]
set -euo pipefail

build=$(cd "$1" && pwd -P)
source=$(cd "$2" && pwd -P)
python=${3:-}
skip=77

scratch=$(mktemp -d "${TMPDIR:-/tmp}/primo-install.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
scratch=$(cd "$scratch" && pwd -P)
for tree in "$source" "$build"; do
  case "$scratch/" in "$tree"/*)
    echo "FAIL: the scratch folder $scratch is inside $tree, where the source tree's files would be found"
    exit 1 ;;
  esac
done

fail() { echo "FAIL: $*"; exit 1; }
step() { echo "--- $* ($SECONDS s)"; }

prefix=$scratch/usr
step "cmake --install $build --prefix $prefix"
cmake --install "$build" --prefix "$prefix" > "$scratch/install.log" || { cat "$scratch/install.log"; fail "cmake --install"; }

data=$prefix/share/primo
for f in bin/primo share/primo/shaders/mesh.vert share/primo/shaders/mesh.frag \
         share/primo/assets/meshes/spot_quadrangulated.obj share/primo/assets/scenarios/bar-bend.json \
         share/applications/primo.desktop share/icons/hicolor/scalable/apps/primo.svg \
         share/mime/packages/primo.xml share/man/man1/primo.1.gz share/doc/primo/LICENSE; do
  [[ -s $prefix/$f ]] || fail "$f was not installed under $prefix"
done
zcat "$prefix/share/man/man1/primo.1.gz" | grep -q '^\.SH' || fail "primo.1.gz is not a man page"
zcat "$prefix/share/man/man1/primo.1.gz" | grep -q 'deform' || fail "the man page does not list the commands"
if command -v desktop-file-validate > /dev/null; then
  desktop-file-validate "$prefix/share/applications/primo.desktop" || fail "primo.desktop is not valid"
fi

# The installed MIME types tell a scenario and a session from other JSON by content.
if command -v update-mime-database > /dev/null && command -v gio > /dev/null; then
  step "MIME types"
  mime=$scratch/mime-share
  mkdir -p "$mime/mime/packages"
  cp "$prefix/share/mime/packages/primo.xml" "$mime/mime/packages/"
  update-mime-database "$mime/mime" > /dev/null 2>&1
  echo '{"format": "something-else"}' > "$scratch/other.json"
  type_of() { XDG_DATA_HOME=$mime XDG_DATA_DIRS=$mime:/usr/share gio info -a standard::content-type "$1" | awk '/content-type/ {print $2}'; }
  expect_type() { [[ $(type_of "$1") == "$2" ]] || fail "$(basename "$1") is $(type_of "$1"), not $2"; }
  expect_type "$data/assets/scenarios/bar-bend.json" application/x-primo-scenario+json
  expect_type "$data/assets/sessions/spot-pose.session.json" application/x-primo-session+json
  expect_type "$scratch/other.json" application/json
  expect_type "$data/assets/meshes/huesitos.fbx" model/x-fbx
fi

# The overrides would hide which folder the installed binary finds by itself.
unset PRIMO_SHADER_DIR PRIMO_ASSET_DIR
export PRIMO_CONFIG_DIR=$scratch/config PRIMO_STATE_DIR=$scratch/state
run=$scratch/run
mkdir -p "$run"
cd "$run"
primo=$prefix/bin/primo

step "installed primo deform on the installed bar-bend.json"
"$primo" deform "$data/assets/scenarios/bar-bend.json" -o bar-bent.obj --stats stats.json \
  || fail "primo deform"
[[ -s bar-bent.obj && -s stats.json ]] || fail "primo deform wrote no mesh or no statistics"
grep -q '^f ' bar-bent.obj || fail "bar-bent.obj has no faces"

if [[ -n $python ]]; then
  step "installed Python module"
  # A prefix other than /usr and /usr/local gets the user-site layout (python/CMakeLists.txt).
  site=$prefix/lib/$("$python" -c 'import sys; print("python%d.%d" % sys.version_info[:2])')/site-packages
  ls "$site"/primo*.so > /dev/null 2>&1 || fail "no Python module in $site"
  found=$(PYTHONPATH=$site "$python" -c 'import primo; print(primo.__file__)') || fail "import primo"
  case "$found" in "$site"/*) ;; *) fail "import primo found $found, not the installed module" ;; esac

  # The installed add-on with the installed module, in Blender when it is there.
  if command -v blender > /dev/null; then
    step "installed Blender add-on"
    "$source/tests/blender/run_blender_test.sh" "$prefix/share/primo/blender/primo_pose.zip" "$site" \
      "$source/tests/blender/test_pose_follows_empty.py" > blender.log 2>&1 \
      || { cat blender.log; fail "the installed add-on in Blender"; }
    grep 'solve now' blender.log
  fi
fi

# The .deb: cpack builds the project first (its preinstall step), which on the built tree ctest
# runs in is a no-op.
if command -v cpack > /dev/null && command -v dpkg-deb > /dev/null; then
  step "cpack -G DEB"
  cpack --config "$build/CPackConfig.cmake" -G DEB -B "$scratch/deb" > "$scratch/cpack.log" 2>&1 \
    || { cat "$scratch/cpack.log"; fail "cpack -G DEB"; }
  deb=$(ls "$scratch"/deb/primo_*.deb)
  dpkg-deb -c "$deb" > contents.txt
  for f in ./usr/bin/primo ./usr/share/primo/shaders/mesh.vert \
           ./usr/share/primo/assets/scenarios/spot-pose.json ./usr/share/applications/primo.desktop \
           ./usr/share/icons/hicolor/scalable/apps/primo.svg ./usr/share/mime/packages/primo.xml \
           ./usr/share/man/man1/primo.1.gz ${python:+./usr/lib/python3/dist-packages/primo.} \
           ${python:+./usr/share/primo/blender/primo_pose.zip}; do
    grep -qF " $f" contents.txt || fail "$f is not in $(basename "$deb")"
  done
  maintainer=$(dpkg-deb -f "$deb" Maintainer)
  [[ $maintainer =~ ^[^\<\>]+\ \<[^@\ ]+@[^@\ ]+\>$ ]] || fail "Maintainer is not 'Name <email>': $maintainer"
  depends=$(dpkg-deb -f "$deb" Depends)
  [[ $depends == *libglfw3* && $depends == *libc6* ]] || fail "Depends lacks libc6 or libglfw3: $depends"
  echo "$(basename "$deb"): $(stat -c %s "$deb") bytes"
  echo "Depends: $depends"
fi

xvfb_run=$(command -v xvfb-run || true)
if [[ -z $xvfb_run ]]; then
  echo "SKIP: xvfb-run not found (Debian package xvfb): the installed editor was not started"
  exit "$skip"
fi
editor() { "$xvfb_run" -a -s "-screen 0 1280x800x24" "$primo" edit "$@"; }

# Without the installed fragment shader the editor must fail naming the installed file: proof
# that it reads its shaders from the install, not from the source tree it was built from.
step "installed editor without an installed shader"
mv "$data/shaders/mesh.frag" "$scratch/mesh.frag"
if editor --screenshot missing.png --timeout 60 > editor-missing.log 2>&1; then
  fail "the editor ran without $data/shaders/mesh.frag (it read another copy)"
fi
grep -qF "$data/shaders/mesh.frag" editor-missing.log \
  || { cat editor-missing.log; fail "the error does not name $data/shaders/mesh.frag"; }
mv "$scratch/mesh.frag" "$data/shaders/mesh.frag"

step "installed editor: screenshot of the bundled Spot"
editor --screenshot spot.png --width 640 --height 480 --timeout 120 > editor.log 2>&1 \
  || { cat editor.log; fail "primo edit --screenshot"; }
[[ -s spot.png ]] || fail "no screenshot"
[[ $(head -c 8 spot.png | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail "spot.png is not a PNG"
echo "screenshot: $(stat -c %s spot.png) bytes"

step "done"
