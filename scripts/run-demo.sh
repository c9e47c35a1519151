#!/usr/bin/env bash
# The main job of `make run`: the lecture's example through arena-sim, then a whole preset.
set -euo pipefail
bin=${1:-build/bin}
echo "== the lecture's example: 10 N on 1 kg, dt = 1 s, explicit Euler (expect x = 450 m) =="
"$bin/arena-sim" --integrator explicit --dt 1 --steps 10 --mass 1 --force 10,0
echo "== the asteroids preset, 1000 rocks, 600 steps =="
"$bin/arena-sim" --preset asteroids --bodies 1000 --steps 600 --seed 1
