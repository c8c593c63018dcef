#!/usr/bin/env bash
# periflex against MuJoCo at equal accuracy on the IFToMM A01 pendulum (2000 s) and A02 double
# four-bar (10 s): writes the two MuJoCo models (MJCF), builds bench/mujoco_compare.cpp in the
# build tree where CMake finds MuJoCo (Debian: libmujoco-dev) and runs it. It prints every
# setting tried, each program's cheapest setting reaching a max position error of 1e-3 m, and
# the CPU time ratio periflex / MuJoCo. Without MuJoCo it says so and exits 0.
#
#   bench/mujoco_compare.sh [--quick] [--only=a01|a02]    (BUILD_DIR: build tree, default build/)
#
# --quick shortens A01 to 200 s and times each choice once (a check that it runs, not a figure).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"

if [[ ! -f "$build/CMakeCache.txt" ]]; then
  echo "mujoco_compare: no configured build tree in $build (run: cmake --preset release)" >&2
  exit 2
fi
# configure again so a MuJoCo installed since is found
cmake "$build" >/dev/null
if ! grep -Eq '^MUJOCO_LIBRARY:FILEPATH=.+' "$build/CMakeCache.txt" ||
   grep -Eq '^MUJOCO_(LIBRARY|INCLUDE_DIR):[A-Z]+=.*NOTFOUND$' "$build/CMakeCache.txt"; then
  echo "mujoco_compare: MuJoCo not found (Debian package libmujoco-dev); nothing to compare"
  exit 0
fi
cmake --build "$build" --target mujoco_compare >/dev/null

models="$(mktemp -d)"
trap 'rm -rf "$models"' EXIT

# A01: a 1 kg point mass on a massless 1 m rod, hinged about y at the origin, released from rest
# with the rod horizontal along +x; gravity along -z. (MuJoCo needs some inertia: 1e-12.)
cat >"$models/a01.xml" <<'EOF'
<mujoco model="a01_pendulum">
  <option gravity="0 0 -9.81">
    <flag contact="disable"/>
  </option>
  <worldbody>
    <body name="rod">
      <joint name="pin" type="hinge" axis="0 1 0"/>
      <inertial pos="1 0 0" mass="1" diaginertia="1e-12 1e-12 1e-12"/>
      <site name="bob" pos="1 0 0"/>
    </body>
  </worldbody>
</mujoco>
EOF

# A02: five uniform 1 m, 1 kg bars as a chain crank0 - coupler1 - crank1 - coupler2 - crank2,
# hinged about y, starting upright / horizontal; crank1 and crank2 closed onto their ground
# pins at x = 1 and x = 2 by connect equalities (MuJoCo's loop closure). Initial joint rates
# (1, -1, 1, -1, 1) rad/s give B0 (the top of crank0) 1 m/s along +x, the couplers none.
bar_z='mass="1" diaginertia="0.08333333333333333 0.08333333333333333 1e-9"'
bar_x='mass="1" diaginertia="1e-9 0.08333333333333333 0.08333333333333333"'
cat >"$models/a02.xml" <<EOF
<mujoco model="a02_double_four_bar">
  <option gravity="0 0 -9.81">
    <flag contact="disable"/>
  </option>
  <default>
    <joint type="hinge" axis="0 1 0"/>
  </default>
  <worldbody>
    <body name="crank0">
      <joint name="pin0"/>
      <inertial pos="0 0 0.5" $bar_z/>
      <site name="b0" pos="0 0 1"/>
      <body name="coupler1" pos="0 0 1">
        <joint name="b0_start1"/>
        <inertial pos="0.5 0 0" $bar_x/>
        <body name="crank1" pos="1 0 0">
          <joint name="end1_b1"/>
          <inertial pos="0 0 -0.5" $bar_z/>
          <body name="coupler2">
            <joint name="b1_start2"/>
            <inertial pos="0.5 0 0" $bar_x/>
            <body name="crank2" pos="1 0 0">
              <joint name="end2_b2"/>
              <inertial pos="0 0 -0.5" $bar_z/>
            </body>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <equality>
    <connect name="pin1" body1="crank1" body2="world" anchor="0 0 -1"/>
    <connect name="pin2" body1="crank2" body2="world" anchor="0 0 -1"/>
  </equality>
</mujoco>
EOF

echo "machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
"$build/bench/mujoco_compare" "$models/a01.xml" "$models/a02.xml" "$@"
