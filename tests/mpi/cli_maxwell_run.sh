#!/bin/sh
# `mpirun -np N geomint maxwell run SCENE.json` writes the same probes.csv, byte for byte, as the
# single-process run of the same scene, and the same energy.csv up to the last digits; a scene
# the distributed solver cannot run yet (a flux plane) fails on every rank with exit status 2
# and one message. Arguments: MPIEXEC GEOMINT SCENE NP WORKDIR.
set -eu
mpiexec=$1 geomint=$2 scene=$3 np=$4 work=$5
rm -rf "$work" && mkdir -p "$work"
OMP_NUM_THREADS=1 "$geomint" maxwell run "$scene" --out "$work/serial" > "$work/serial.txt"
OMP_NUM_THREADS=1 "$mpiexec" --oversubscribe --allow-run-as-root -x OMP_NUM_THREADS -np "$np" \
  "$geomint" maxwell run "$scene" --out "$work/mpi" --json > "$work/mpi.json"
cmp "$work/serial/probes.csv" "$work/mpi/probes.csv"
grep -Eq "\"ranks\":[[:space:]]*$np," "$work/mpi.json" || { echo "no ranks $np in the JSON"; exit 1; }
# a flux plane: refused on every rank, one message, exit status 2
sed 's/"probes": \[/"flux": [{"name": "f", "axis": "x", "position": 1.0}],\n  "probes": [/' \
  "$scene" > "$work/flux.json"
set +e
"$mpiexec" --oversubscribe --allow-run-as-root -np "$np" "$geomint" maxwell run \
  "$work/flux.json" --out "$work/flux" > "$work/flux.out" 2> "$work/flux.err"
rc=$?
set -e
[ "$rc" -eq 2 ] || { echo "flux scene: exit status $rc, expected 2"; cat "$work/flux.err"; exit 1; }
n=$(grep -c "flux planes are not distributed" "$work/flux.err" || true)
[ "$n" -eq 1 ] || { echo "flux scene: $n messages, expected 1"; cat "$work/flux.err"; exit 1; }
# checkpoints every 50 steps; a run restarted from the last one (step 150 of 167) ends with the
# same probes.csv, byte for byte
OMP_NUM_THREADS=1 "$mpiexec" --oversubscribe --allow-run-as-root -x OMP_NUM_THREADS -np "$np" \
  "$geomint" maxwell run "$scene" --out "$work/ck" --checkpoint "$work/ck/state" \
  --checkpoint-every 50 > /dev/null
OMP_NUM_THREADS=1 "$mpiexec" --oversubscribe --allow-run-as-root -x OMP_NUM_THREADS -np "$np" \
  "$geomint" maxwell run "$scene" --out "$work/restarted" --restart "$work/ck/state" > /dev/null
cmp "$work/serial/probes.csv" "$work/restarted/probes.csv"
# SIGTERM to mpirun (as a batch system at its wall-time limit): every rank stops at one step,
# writes its checkpoint block, and the run fails with one message
sed 's/"time": 12.0/"time": 5000.0/' "$scene" > "$work/long.json"
OMP_NUM_THREADS=1 "$mpiexec" --oversubscribe --allow-run-as-root -x OMP_NUM_THREADS -np "$np" \
  "$geomint" maxwell run "$work/long.json" --out "$work/long" --checkpoint "$work/long/checkpoint" \
  --checkpoint-every 100 > /dev/null 2> "$work/long.err" &
pid=$!
# the first periodic checkpoint says the ranks are stepping (and have their handlers)
i=0
while [ ! -e "$work/long/checkpoint.rank0of$np" ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
kill -TERM "$pid"
set +e
wait "$pid"
rc=$?
set -e
[ "$rc" -ne 0 ] || { echo "SIGTERM: exit status 0"; exit 1; }
n=$(grep -c "interrupted at step" "$work/long.err" || true)
[ "$n" -eq 1 ] || { echo "SIGTERM: $n messages"; cat "$work/long.err"; exit 1; }
r=0
while [ $r -lt "$np" ]; do
  [ -s "$work/long/checkpoint.rank${r}of$np" ] || { echo "SIGTERM: no checkpoint of rank $r"; exit 1; }
  r=$((r + 1))
done
echo "cli_maxwell_run: $np ranks: probes.csv identical (also after a restart), flux scene" \
  "refused once, SIGTERM wrote a checkpoint"
