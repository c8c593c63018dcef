#!/usr/bin/env bash
# The Debian package installed for real, as a user would: built from the Release build, installed
# with apt-get, run from another folder with no variable set, then removed. Needs root; CI runs it
# after the suite (the suite itself only builds, inspects and unpacks the package).
set -euo pipefail
cd "$(dirname "$0")/.."
(cd build && rm -f periflex_*.deb && cpack -G DEB >/dev/null)
deb=$(ls "$PWD"/build/periflex_*.deb)
export DEBIAN_FRONTEND=noninteractive
apt-get install -y -q "$deb" >/dev/null
trap 'apt-get remove -y -q periflex >/dev/null' EXIT
work=$(mktemp -d)
cd "$work"
unset PERIFLEX_ROOT
command -v periflex
periflex --version | grep -qx "files: /usr/share/periflex"
periflex run /usr/share/periflex/scenes/pendulum.toml --until 0.05 --out run --quiet
periflex run /usr/share/periflex/scenes/notched_plate.toml --until 2e-6 --frame-every 5e-7 --movie plate.mp4 --out movie --quiet
test -s plate.mp4
echo "package: installed with apt-get, ran from $work, removed"
