#!/usr/bin/env bash
# The program as a user installs it, run from a folder of its own with no variable set.
#   install_check.sh prefix BUILD WORK   cmake --install to WORK/first, moved to WORK/moved
#   install_check.sh deb BUILD WORK      cpack -G DEB, inspected with dpkg-deb, unpacked to WORK/deb
# Either way the installed program must find its own files (--version names them), run a scene,
# draw a movie off-screen (when ffmpeg is there) and open the window under Xvfb (when present).
set -uo pipefail
mode=$1 build=$2 work=$3/$1

fail() { echo "FAIL ($mode): $*" >&2; exit 1; }

rm -rf "$work" && mkdir -p "$work/elsewhere" || fail "cannot make $work"
if [[ $mode == prefix ]]; then
  cmake --install "$build" --prefix "$work/first" >"$work/install.log" 2>&1 || fail "cmake --install: $(tail -3 "$work/install.log")"
  mv "$work/first" "$work/moved" || fail "cannot move the prefix"
  prefix=$work/moved
else
  (cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" >"$work/cpack.log" 2>&1) || fail "cpack: $(tail -5 "$work/cpack.log")"
  deb=$(ls "$work"/periflex_*.deb 2>/dev/null | head -1)
  [[ -f $deb ]] || fail "cpack wrote no periflex_*.deb: $(tail -5 "$work/cpack.log")"
  info=$(dpkg-deb --info "$deb") || fail "dpkg-deb --info cannot read $deb"
  echo "$info"
  # the libraries the program links, declared from the binary
  depends=$(echo "$info" | sed -n 's/^ Depends: //p')
  for lib in libc6 libstdc++6 libgomp1 libdeflate0 libcholmod; do
    [[ $depends == *"$lib"* ]] || fail "Depends lacks $lib: '$depends'"
  done
  contents=$(dpkg-deb --contents "$deb")
  for path in ./usr/bin/periflex ./usr/share/periflex/shaders/ ./usr/share/periflex/scenes/notched_plate.toml \
              ./usr/share/periflex/assets/colormaps/turbo.png ./usr/share/doc/periflex/README.md; do
    grep -q " $path\$" <<<"$contents" || fail "the package lacks $path"
  done
  dpkg-deb -x "$deb" "$work/deb" || fail "dpkg-deb -x failed"
  prefix=$work/deb/usr
fi

program=$prefix/bin/periflex
scenes=$prefix/share/periflex/scenes
cd "$work/elsewhere" || fail "no folder to run in"
unset PERIFLEX_ROOT

# the program names the files it found: those of its own prefix, not the source tree
version=$("$program" --version) || fail "--version failed"
echo "$version"
[[ $version == *"files: $prefix/share/periflex"* ]] || fail "the program does not use its own files: '$version'"

"$program" run "$scenes/pendulum.toml" --until 0.05 --out run --quiet || fail "run exited $?"
[[ $(wc -l <run/series.csv) -gt 2 ]] || fail "run wrote no rows"

if command -v ffmpeg >/dev/null; then
  "$program" run "$scenes/notched_plate.toml" --until 2e-6 --frame-every 5e-7 --movie plate.mp4 --out movie --quiet \
    || fail "run --movie exited $?"
  [[ -s plate.mp4 ]] || fail "no movie written"
fi

if command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 800x600x24" "$program" gui "$scenes/flexible_pendulum.toml" --frames 3 \
    --screenshot window.png >gui.log 2>&1 || fail "gui exited $?: $(tail -3 gui.log)"
  [[ -s window.png ]] || fail "the window wrote no screenshot"
fi
# the Python module, when it was built: imported from the moved prefix and stepped
package=$prefix/lib/python3/dist-packages
if [[ -f $package/periflex/__init__.py ]]; then
  python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
  PYTHONPATH=$package "${python:-python3}" -c "
import periflex
sim = periflex.Simulation('$scenes/pendulum.toml')
sim.step(10)
assert sim.steps == 10 and sim.body_poses.shape == (1, 3)
# its files, its pictures and the program its sweeps start: those of the moved prefix
assert str(periflex.scenes_folder()) == '$prefix/share/periflex/scenes', periflex.scenes_folder()
assert periflex._commands._program() == '$prefix/bin/periflex', periflex._commands._program()
if periflex.render_available():
    assert sim.render(64, 48).shape == (48, 64, 3)
print('python module:', periflex.__file__)" || fail "the installed Python module does not run"
fi
echo "PASS ($mode): $prefix"
