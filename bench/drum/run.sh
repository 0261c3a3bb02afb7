#!/usr/bin/env bash
# Serial rotating-drum benchmark: grains vs LIGGGHTS on the scene of
# cases/rotating_drum (1,800 spheres, d = 3 mm, in a closed drum of radius
# 50 mm and length 24 mm given as an STL mesh of 384 triangles, turning at
# 10 rpm about +y), both serial (OMP_NUM_THREADS=1, one MPI rank), the same
# initial positions, the same force law, the same time step and number of
# steps. Prints the particle-steps per second of wall time of both, their
# ratio (grains / LIGGGHTS), the CPU-time figures, the stage breakdowns, the
# particles still inside the drum at the end, and `uptime` before and after.
#
#   bash bench/drum/run.sh            (about 2-5 minutes on one core at END=2)
#   ANGLE=1 bash bench/drum/run.sh    (physics check, END=6 by default, about 3 minutes:
#                                      the dynamic angle of repose of both codes)
#
# What is compared and how:
#  - Scene and parameters are read from the case file (bench/drum/scene.py
#    params): N, r, rho, E, nu, e, mu (particles and drum: one material), no
#    rolling friction, gravity, time step 0.2 Rayleigh times (grains computes
#    it; LIGGGHTS is given the dt grains printed in summary.json, 10 digits),
#    neighbour skin 0.1 d in both, rebuilt when a particle has moved half the
#    skin (LIGGGHTS: neigh_modify delay 0 every 1 check yes).
#  - Rotation: LIGGGHTS cannot ramp a mesh rotation, so BOTH codes turn the
#    drum at the full 10 rpm from t = 0 (grains: --set walls.0.start=0 --set
#    walls.0.ramp=0; LIGGGHTS: fix move/mesh ... rotate, period 60/rpm s,
#    right-handed about the case's axis as grains's rpm) instead of the case's
#    0.5 s at rest + 0.5 s ramp. The spheres fall into the turning drum (about
#    0.15 s), settle, and the rest of the END seconds (default 2 s) is the
#    rotating bed (the case at rest then spun up would give the same bed).
#  - Initial positions: one set for both (bench/drum/scene.py positions, i.e.
#    bench/pour/gen_positions.py's random sequential addition in the case's
#    fill region with the case's seed): grains reads it with placement
#    {type: file} (case rewritten by bench/pour/scene.py case, which also cuts
#    the output to the first and last VTK frame, no wall loads, no progress
#    line), LIGGGHTS with read_data.
#  - Drum: the case's STL for both (converted to ASCII STL for LIGGGHTS, which
#    reads no binary STL): fix mesh/surface + fix wall/gran model hertz
#    tangential history mesh ... limitForce on + fix move/mesh rotate.
#  - Force law: Hertz + Mindlin tangential spring with Coulomb limit, normal
#    force clamped at zero, restitution-based damping. LIGGGHTS is given the
#    restitution whose damping coefficient equals the one grains calibrates for
#    the case's e (bench/pour/match_damping.py: e = 0.5 -> 0.4363), as in
#    bench/pour (pair_style / fix property/global lines copied from there).
#  - Timing: grains's summary.json particle_steps_per_second (its whole run
#    loop, first and last VTK frame included); LIGGGHTS N x steps / "Loop time"
#    (no dumps in the timed run; the final positions are dumped by a separate
#    `run 0`; screen output to a file: LIGGGHTS 3.8 crashes reading an STL
#    with -screen none). Also user+sys CPU seconds of each whole process, less sensitive
#    to other jobs on a shared machine.
#  - Sanity check: particles left at the end (grains lost_particles, LIGGGHTS
#    atom count; boundary f f f drops atoms leaving the box) and, from the final
#    positions of both, those inside the drum (centre within the drum radius
#    minus r/2 of the axis and between the end caps) and the bed's mean x, z
#    (the same sign of mean x in both = the same sense of rotation).
#  Differences that remain (not removable from the inputs): as in bench/pour
#  (RESULTS.md): tangential-spring update (grains rotates and keeps its
#  length, LIGGGHTS projects), Coulomb limit (grains limits spring + damping,
#  LIGGGHTS the spring only); plus the mesh contact algorithms themselves
#  (grains: one contact per physical contact at a face, edge or vertex with the
#  history carried from triangle to triangle; LIGGGHTS: its own triangle
#  neighbour list and edge/corner handling), so the two beds agree
#  statistically, not particle by particle.
#
#
# ANGLE=1: a cross-code check of the physics instead of a throughput figure
# (its timings include frame output and are not the benchmark's). Both codes
# write frames every FRAME_EVERY s (default 0.1) at the same steps (every
# llround(FRAME_EVERY / dt) steps, and the last step): grains its VTK frames
# (output.every; grains has no output start time, so from t = 0), LIGGGHTS a
# `dump custom ... id x y z radius` from the first such step at or after
# FRAMES_FROM (default 2 s; its run is split there: run S0, dump, run the
# rest), plus its final dump as the last frame. Then the dynamic angle of
# repose of the free surface, for the frames at t >= ANGLE_FROM (default 3 s),
# is measured the same way in both: `grains repose OUTDIR --axis y` for
# grains, bench/drum/surface_angle.py (the same method in Python) for
# LIGGGHTS, with the same centre (the drum's axis point), drum radius (its
# STL's), column width (2 mean diameters) and span (0.6 R). The Python method
# is checked on grains's own frames against grains repose (per frame, to
# 0.01 deg; both with these options and with grains repose's defaults). Prints
# mean +- std over the frames, the standard error, the difference, and the
# bed's mean centre (x, z) in the last frame.
#
# Environment: GRAINS (binary, default build/grains, built with the grains
# target only if missing), END (simulated seconds, default 2.0; 6.0 with
# ANGLE=1, one revolution at 10 rpm), WORK (scratch, default
# ${TMPDIR:-/tmp}/grains-bench-drum, or grains-bench-drum-angle with ANGLE=1;
# wiped), LIGGGHTS (default liggghts), CASE (default
# cases/rotating_drum/case.yaml), ANGLE (0 or 1), FRAME_EVERY, FRAMES_FROM,
# ANGLE_FROM (ANGLE=1 only, see above).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
GRAINS="${GRAINS:-$ROOT/build/grains}"
ANGLE="${ANGLE:-0}"
if [ "$ANGLE" = 1 ]; then
  END="${END:-6.0}"
  WORK="${WORK:-${TMPDIR:-/tmp}/grains-bench-drum-angle}"
  FRAME_EVERY="${FRAME_EVERY:-0.1}"; FRAMES_FROM="${FRAMES_FROM:-2.0}"; ANGLE_FROM="${ANGLE_FROM:-3.0}"
elif [ "$ANGLE" = 0 ]; then
  END="${END:-2.0}"
  WORK="${WORK:-${TMPDIR:-/tmp}/grains-bench-drum}"
else
  echo "ANGLE must be 0 or 1" >&2; exit 2
fi
LIGGGHTS="${LIGGGHTS:-liggghts}"
CASE="${CASE:-$ROOT/cases/rotating_drum/case.yaml}"
export OMP_NUM_THREADS=1   # serial comparison
export PYTHONDONTWRITEBYTECODE=1

echo "== load before: $(uptime)"

if [ ! -x "$GRAINS" ]; then
  cmake --build "$(dirname "$GRAINS")" --target grains -j2 >/dev/null
fi
echo "== grains: $("$GRAINS" --version 2>&1 | head -1) ($GRAINS)"
command -v "$LIGGGHTS" >/dev/null || { echo "LIGGGHTS not found: apt-get install --no-install-recommends liggghts" >&2; exit 1; }

# The scene, read from the case file (one source of truth).
eval "$(python3 "$HERE/scene.py" params "$CASE")"
rm -rf "$WORK"; mkdir -p "$WORK/grains" "$WORK/liggghts"; WORK="$(cd "$WORK" && pwd)"

# (a) One set of initial positions, for both codes; the drum for both.
python3 "$HERE/scene.py" positions "$CASE" "$WORK"
cp "$MESH" "$WORK/$(basename "$MESH")"                       # grains: next to its case file
python3 "$HERE/scene.py" stl "$MESH" "$WORK/liggghts/drum.stl"  # LIGGGHTS: ASCII STL

cpu_seconds() {  # cpu_seconds FILE CMD...: runs CMD, writes its user+sys CPU seconds to FILE
  python3 -c "
import resource, subprocess, sys
r = subprocess.run(sys.argv[2:]).returncode
u = resource.getrusage(resource.RUSAGE_CHILDREN)
open(sys.argv[1], 'w').write('%.3f\\n' % (u.ru_utime + u.ru_stime))
sys.exit(r)" "$@"
}
json() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$WORK/grains/summary.json" "$1"; }

# (b) grains: the case with placement {type: file}, first and last frame only,
# the drum at full speed from t = 0.
python3 "$ROOT/bench/pour/scene.py" case "$CASE" positions.txt "$WORK/case.yaml"
if [ "$ANGLE" = 1 ]; then  # frames every FRAME_EVERY s instead of the first and last only
  grep -q '^  every_steps: 1000000000$' "$WORK/case.yaml" || { echo "unexpected output block in $WORK/case.yaml" >&2; exit 1; }
  sed -i "s/^  every_steps: 1000000000\$/  every: $FRAME_EVERY/" "$WORK/case.yaml"
fi
GSET=(--set "time.end=$END" --set walls.0.start=0 --set walls.0.ramp=0)
echo "== grains: $GRAINS run $WORK/case.yaml -o $WORK/grains -q ${GSET[*]}"
cpu_seconds "$WORK/grains.cpu" "$GRAINS" run "$WORK/case.yaml" -o "$WORK/grains" -q "${GSET[@]}"
DT=$(json time_step_s); STEPS=$(json steps)

# (c) LIGGGHTS, serial, same scene, physics, dt and number of steps.
read -r DAMPING E_LIGGGHTS < <(python3 "$ROOT/bench/pour/match_damping.py" "$REST")
PERIOD=$(python3 -c "print(repr(60.0 / $RPM))")
read -r G GDIR < <(python3 -c "
import math; g = ($G_X, $G_Y, $G_Z); n = math.sqrt(sum(v * v for v in g))
print(repr(n), ' '.join(repr(v / n) for v in g))")
sed -e "s#@DATA@#$WORK/atoms.data#; s#@SKIN@#$SKIN#g; s#@E@#$E#; s#@NU@#$NU#; s#@MU@#$MU#; s#@REST@#$REST#" \
    -e "s#@E_LIGGGHTS@#$E_LIGGGHTS#; s#@DT@#$DT#; s#@STEPS@#$STEPS#g; s#@MESH@#$WORK/liggghts/drum.stl#" \
    -e "s#@RPM@#$RPM#; s#@PERIOD@#$PERIOD#g; s#@AXIS_POINT@#$AXIS_POINT#; s#@AXIS@#$AXIS#" \
    -e "s#@G@#$G#; s#@GDIR@#$GDIR#; s#@DUMP@#$WORK/liggghts/final.dump#" "$HERE/in.liggghts" > "$WORK/liggghts/in.liggghts"
echo "== LIGGGHTS: $LIGGGHTS -in $WORK/liggghts/in.liggghts -log $WORK/liggghts/log.liggghts -echo none -screen screen.liggghts"
if [ "$ANGLE" = 1 ]; then
  # Frames at grains's frame steps (multiples of NF = llround(FRAME_EVERY / dt)) from
  # the first one at or after FRAMES_FROM: the run is split there.
  read -r NF S0 < <(python3 -c "
import math; dt, n = $DT, max(1, round($FRAME_EVERY / $DT)); k = math.ceil($FRAMES_FROM / dt / n - 1e-9)
print(n, k * n)")
  [ "$S0" -lt "$STEPS" ] || { echo "FRAMES_FROM=$FRAMES_FROM lies after END=$END" >&2; exit 1; }
  mkdir -p "$WORK/liggghts/frames"
  python3 - "$WORK/liggghts/in.liggghts" "$STEPS" "$S0" "$NF" "$WORK/liggghts/frames" <<'PY'
import sys
path, steps, s0, nf, d = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5]
t = open(path).read().splitlines()
k = [i for i, s in enumerate(t) if s.split() == ["run", str(steps)]]
assert len(k) == 1, "in.liggghts: expected one 'run %d' line" % steps
block = (["run             %d" % s0] if s0 > 0 else []) + [
    "# ANGLE=1 (bench/drum/run.sh): frames for the angle of repose, at grains's frame steps",
    "dump            frames all custom %s %s/frame.*.dump id x y z radius" % (nf, d),
    "dump_modify     frames sort id",
    "run             %d" % (steps - s0),
    "undump          frames"]
open(path, "w").write("\n".join(t[:k[0]] + block + t[k[0] + 1:]) + "\n")
PY
  echo "== ANGLE=1: frames every $NF steps ($FRAME_EVERY s); LIGGGHTS from step $S0, run split there"
fi
(cd "$WORK/liggghts" && cpu_seconds "$WORK/liggghts.cpu" "$LIGGGHTS" -in in.liggghts -log log.liggghts -echo none -screen screen.liggghts)

# (d) Figures.
G_RATE=$(json particle_steps_per_second); G_WALL=$(json wall_time_s)
G_LOST=$(json lost_particles); G_END=$(json particles_end)
LOOP=$(grep -m1 '^Loop time of' "$WORK/liggghts/log.liggghts" || true)
if [ -z "$LOOP" ]; then echo "LIGGGHTS failed:" >&2; tail -5 "$WORK/liggghts/log.liggghts" >&2; exit 1; fi
L_TIME=$(echo "$LOOP" | awk '{print $4}'); L_STEPS=$(echo "$LOOP" | awk '{print $9}'); L_ATOMS=$(echo "$LOOP" | awk '{print $12}')
if [ "$ANGLE" = 1 ]; then  # the split run: the sums of its parts (the final 'run 0' adds nothing)
  read -r L_TIME L_STEPS < <(awk '/^Loop time of/{t += $4; n += $9} END{print t, n}' "$WORK/liggghts/log.liggghts")
  L_ATOMS=$(grep '^Loop time of' "$WORK/liggghts/log.liggghts" | awk '$9 > 0' | tail -1 | awk '{print $12}')
  echo
  echo "== ANGLE=1: the timings below include frame output (and LIGGGHTS's run is split): NOT the benchmark figures"
fi
L_RATE=$(python3 -c "print($N * $L_STEPS / $L_TIME)")
RATIO=$(python3 -c "print('%.3f' % ($G_RATE / $L_RATE))")

echo
echo "== scene: N = $N, d = $(python3 -c "print(2*$R)") m, rho = $RHO, E = $E, nu = $NU, e = $REST (LIGGGHTS: $E_LIGGGHTS, same damping a = $DAMPING), mu = $MU"
echo "   dt = $DT s, $STEPS steps (t = $(python3 -c "print('%.4f' % ($STEPS * $DT))") s), skin $SKIN m, drum $RPM rpm about [$AXIS] from t = 0 (period $PERIOD s)"
printf "grains:   %10.0f particle-steps/s  (%s steps in %.2f s wall, %s particles at the end, lost %s)\n" "$G_RATE" "$STEPS" "$G_WALL" "$G_END" "$G_LOST"
printf "LIGGGHTS: %10.0f particle-steps/s  (%s steps in %.2f s wall, %s atoms at the end)\n" "$L_RATE" "$L_STEPS" "$L_TIME" "$L_ATOMS"
echo "ratio grains/LIGGGHTS (wall): $RATIO"
G_CPU=$(cat "$WORK/grains.cpu"); L_CPU=$(cat "$WORK/liggghts.cpu")
python3 -c "
g, l = $N * $STEPS / $G_CPU, $N * $L_STEPS / $L_CPU
print('per CPU second (whole process, set-up included): grains %.0f (%.2f s), LIGGGHTS %.0f (%.2f s), ratio %.3f' % (g, $G_CPU, l, $L_CPU, g / l))"
echo "grains stage seconds:"
python3 -c "
import json,sys
s=json.load(open(sys.argv[1]))['stage_seconds']
for k,v in s.items(): print('  %8.2f  %s' % (v,k))" "$WORK/grains/summary.json"
echo "LIGGGHTS breakdown:"; awk '/^Loop time of/{n++} n==1 && /^(Pair|Neigh|Comm|Outpt|Other|Modify) +time/' "$WORK/liggghts/log.liggghts" | sed 's/^/  /'
grep -E '^Neighbor list builds' "$WORK/liggghts/log.liggghts" | head -1 | sed 's/^/  LIGGGHTS /'
echo "  grains neighbor builds = $(json neighbor_builds)"

LAST=$(ls "$WORK"/grains/frames/particles_*.vtu | sort | tail -1)
read -r GN GIN GX GZ < <(python3 "$HERE/scene.py" bed grains "$LAST" "$CASE")
read -r LN LIN LX LZ < <(python3 "$HERE/scene.py" bed liggghts "$WORK/liggghts/final.dump" "$CASE")
echo "final bed (inside: centre within the drum; mean x, z of the centres, m):"
echo "  grains   $GIN of $GN inside, mean x $GX, mean z $GZ"
echo "  LIGGGHTS $LIN of $LN inside, mean x $LX, mean z $LZ"

if [ "$ANGLE" = 1 ]; then
  # (e) The dynamic angle of repose, measured the same way for both codes.
  A="$WORK/angle"; mkdir -p "$A"
  [ -f "$WORK/liggghts/frames/frame.$STEPS.dump" ] || cp "$WORK/liggghts/final.dump" "$WORK/liggghts/frames/frame.$STEPS.dump"
  CENTRE=$(echo "$AXIS_POINT" | tr ' ' ',')
  OPTS=(--axis y --centre "$CENTRE" --radius "$DRUM_R" --from "$ANGLE_FROM")
  SA="$HERE/surface_angle.py"
  echo
  echo "== angle of repose, frames at t >= $ANGLE_FROM s: centre $CENTRE, drum radius $DRUM_R m (its STL), span 0.6 R, columns 2 mean diameters"
  echo "-- grains: $GRAINS repose $WORK/grains ${OPTS[*]} -o $A/grains"
  "$GRAINS" repose "$WORK/grains" "${OPTS[@]}" -o "$A/grains"
  COLUMN=$(python3 -c "import json,sys; print(repr(json.load(open(sys.argv[1]))['column_m']))" "$A/grains/repose.json")
  echo "-- LIGGGHTS: surface_angle.py liggghts $WORK/liggghts/frames --dt $DT ${OPTS[*]} --column $COLUMN -o $A/liggghts"
  python3 "$SA" liggghts "$WORK/liggghts/frames" --dt "$DT" "${OPTS[@]}" --column "$COLUMN" -o "$A/liggghts"
  echo "-- check of surface_angle.py on grains's frames against grains repose (per frame, tolerance 0.01 deg):"
  python3 "$SA" grains "$WORK/grains" "${OPTS[@]}" -o "$A/grains_py" >/dev/null
  printf "   same options:            "; CHECK1=0; python3 "$SA" compare "$A/grains_py/repose.csv" "$A/grains/repose.csv" || CHECK1=$?
  "$GRAINS" repose "$WORK/grains" --axis y --from "$ANGLE_FROM" -o "$A/grains_default" >/dev/null
  python3 "$SA" grains "$WORK/grains" --axis y --centre "$CENTRE" --from "$ANGLE_FROM" -o "$A/grains_py_default" >/dev/null
  printf "   grains repose defaults:  "; CHECK2=0; python3 "$SA" compare "$A/grains_py_default/repose.csv" "$A/grains_default/repose.csv" || CHECK2=$?
  python3 - "$A" <<'PY'
import json, math, sys
a = sys.argv[1]
g = json.load(open(a + "/grains/repose.json"))
l = json.load(open(a + "/liggghts/repose.json"))
gp = json.load(open(a + "/grains_py/repose.json"))  # grains's frames through the Python reader: its bed centre
print("angle of repose (mean +- std over the frames; SE = std / sqrt(frames), a lower bound: frames are correlated):")
for name, s, last in (("grains", g, gp["last_frame"]), ("LIGGGHTS", l, l["last_frame"])):
    print("  %-9s %6.2f +- %.2f deg  SE %.2f  (%d frames, t = %.3f .. %.3f s, higher on the %s side; "
          "last frame t = %.3f s: bed centre x %.5f m, z %.5f m)" % (
              name, s["mean_deg"], s["std_deg"], s["standard_error_deg"], s["frames"], s["from_s"], s["to_s"],
              s["higher_side"], last["time_s"], last["bed_x_m"], last["bed_z_m"]))
d = g["mean_deg"] - l["mean_deg"]
se = math.hypot(g["standard_error_deg"], l["standard_error_deg"])
print("  difference grains - LIGGGHTS: %+.2f deg +- %.2f (combined SE; %.1f SE)" % (d, se, abs(d) / se if se else float("inf")))
print("  column %g m, span %g, radius %g m, centre %s (grains) / column %g m, span %g, radius %g m, centre %s (LIGGGHTS)" % (
    g["column_m"], g["span"], g["radius_m"], g["centre"], l["column_m"], l["span"], l["radius_m"], l["centre"]))
PY
  [ "$CHECK1" = 0 ] && [ "$CHECK2" = 0 ] || echo "WARNING: surface_angle.py does not reproduce grains repose on grains's frames" >&2
fi
echo "== load after: $(uptime)"
