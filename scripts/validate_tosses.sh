#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Reproduces docs/validation.md: fits friction and restitution to the measured cube tosses
# (impulse fit, from 0.2 and 0.2), replays every toss with the fitted values (impulse replay) and
# draws measured against simulated height and rotation for a few tosses into
# docs/figures/tosses.png. Builds impulse first if needed.
#
#   scripts/validate_tosses.sh [TOSSES_DIR]     (default: ../shared/realworld/tosses beside the repository)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
impulse="${IMPULSE:-$root/build/impulse}"
tosses=${1:-$root/../shared/realworld/tosses}
if [ ! -d "$tosses" ]; then
  echo "validate_tosses.sh: $tosses: no such directory; give the directory of the measured tosses" >&2
  exit 2
fi
[ -x "$impulse" ] || "$root/scripts/build.sh"
# Debian's python3, which has the matplotlib scripts/install-deps.sh installs, if the first
# python3 on the path (a virtual environment, say) lacks it
python=${PYTHON:-python3}
"$python" -c 'import matplotlib' 2> /dev/null || python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The template with friction and restitution set (cube and board alike).
with_coefficients() { # template out friction restitution
  "$python" - "$@" <<'EOF'
import json, sys
template, out, friction, restitution = sys.argv[1:5]
scene = json.load(open(template))
for material in scene["materials"].values():
    material["friction"], material["restitution"] = float(friction), float(restitution)
json.dump(scene, open(out, "w"), indent=1)
EOF
}

with_coefficients "$root/scenes/cube_toss.json" "$work/start.json" 0.2 0.2
"$impulse" fit "$tosses" --scene "$work/start.json" --json "$work/fit.json"
read -r friction restitution < <("$python" -c '
import json, sys
after = json.load(open(sys.argv[1]))["after"]
print(after["friction"], after["restitution"])' "$work/fit.json")

with_coefficients "$root/scenes/cube_toss.json" "$work/fitted.json" "$friction" "$restitution"
echo
"$impulse" replay "$tosses" --scene "$work/fitted.json" --out "$work/simulated" --json "$work/replay.json" |
  tail -n 2
# a toss replayed closely, two typical ones (near the median errors), and one where the real cube
# tumbles over its leading edge onto the next face and the simulated one falls back
"$python" "$root/scripts/plot_tosses.py" "$tosses" "$work/simulated" "$root/docs/figures/tosses.png" 156 486 242 234
echo "wrote $root/docs/figures/tosses.png"
