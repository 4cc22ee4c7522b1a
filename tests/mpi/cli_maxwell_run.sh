#!/bin/sh
# `mpirun -np N geomint maxwell run SCENE.json` writes the same probes.csv, byte for byte, as the
# single-process run of the same scene, and the same energy.csv up to the last digits; a scene
# the distributed solver cannot run yet (a flux plane) fails on every rank with exit status 2
# and one message; write errors stop every rank with one message and exit status 1.
# Arguments: MPIEXEC GEOMINT SCENE NP WORKDIR.
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
sed 's/"time": 12.0/"time": 5000.0/; s/"eps_averaging": true/"eps_averaging": false/' "$scene" \
  > "$work/long.json" # (the staircase: a quicker start under load)
OMP_NUM_THREADS=1 "$mpiexec" --oversubscribe --allow-run-as-root -x OMP_NUM_THREADS -np "$np" \
  "$geomint" maxwell run "$work/long.json" --out "$work/long" --checkpoint "$work/long/checkpoint" \
  --checkpoint-every 100 > /dev/null 2> "$work/long.err" &
pid=$!
# the first periodic checkpoint says the ranks are stepping (and have their handlers)
i=0
while [ ! -e "$work/long/checkpoint.rank0of$np" ] && [ $i -lt 1800 ]; do sleep 0.1; i=$((i + 1)); done
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
# write errors (issue 27: a rank that fails stops all ranks with one message, exit status 1):
# the output directory under a file, probes.csv that is a directory (rank 0 fails after the run),
# a checkpoint that cannot be written (every rank fails at step 50); none may hang (CTest timeout)
write_error() { # NAME EXPECTED-TEXT ARGS...
  name=$1 text=$2
  shift 2
  set +e
  OMP_NUM_THREADS=1 "$mpiexec" --oversubscribe --allow-run-as-root -x OMP_NUM_THREADS -np "$np" \
    "$geomint" maxwell run "$scene" "$@" > /dev/null 2> "$work/$name.err"
  rc=$?
  set -e
  [ "$rc" -eq 1 ] || { echo "$name: exit status $rc, expected 1"; cat "$work/$name.err"; exit 1; }
  n=$(grep -c "^geomint maxwell run: " "$work/$name.err" || true)
  t=$(grep -c "$text" "$work/$name.err" || true)
  [ "$n" -eq 1 ] && [ "$t" -eq 1 ] ||
    { echo "$name: $n messages ($t with '$text'), expected 1"; cat "$work/$name.err"; exit 1; }
}
: > "$work/a_file"
write_error out_under_file "cannot create directory" --out "$work/a_file/out"
mkdir -p "$work/probes_dir/probes.csv"
write_error probes_is_dir "probes.csv' for writing" --out "$work/probes_dir"
write_error checkpoint_under_file "rank 0: checkpoint: cannot write" --out "$work/ck_bad" \
  --checkpoint "$work/a_file/ck" --checkpoint-every 50
echo "cli_maxwell_run: $np ranks: probes.csv identical (also after a restart), flux scene" \
  "refused once, SIGTERM wrote a checkpoint, write errors stop every rank with one message"
