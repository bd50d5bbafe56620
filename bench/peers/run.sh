#!/usr/bin/env bash
# Peer throughput benchmark on the dem-bench scene (issue 5): LAMMPS gran/hertz/history,
# LAMMPS granular (hertz/material + mindlin), LIGGGHTS 3.8 hertz/history and our dem-bench,
# 1 and 2 processes (MPI ranks / threads), interleaved, REPS rounds.
# Each run starts only when the 1-minute load average is below LOADMAX (waits up to WAITMAX s,
# then runs anyway and marks the run 'busy').
# usage: bench/peers/run.sh [REPS=3]        env: LOADMAX=0.5 WAITMAX=300 DEMBENCH=... OUT=...
set -u
cd "$(dirname "$0")"
HERE=$(pwd)
REPS=${1:-3}
LOADMAX=${LOADMAX:-0.5}
WAITMAX=${WAITMAX:-300}
CSV=${CSV:-$HERE/../../../shared/bench/dense20k.csv}
DEMBENCH=${DEMBENCH:-$HERE/../../build/bin/dem-bench}
OUT=${OUT:-$HERE/results}
export OMP_NUM_THREADS=1
mkdir -p "$OUT/logs"
RES="$OUT/runs.tsv"

python3 csv2lammps.py "$CSV" dense20k.data 2> "$OUT/scene.txt"
python3 params.py > "$OUT/params.txt"

{
  echo "# $(date -u +%FT%TZ)  $(lscpu | sed -n 's/^Model name:[[:space:]]*//p')  nproc=$(nproc --all)"
  echo "# lammps $(dpkg-query -W -f='${Version}' lammps 2>/dev/null)  liggghts $(dpkg-query -W -f='${Version}' liggghts 2>/dev/null)  openmpi $(dpkg-query -W -f='${Version}' openmpi-bin 2>/dev/null)"
  printf "code\tnp\trep\tload1\tbusy\tloop_s\tpsteps_per_s\tcontacts_per_particle\tmax_rss_kb\n"
} > "$RES"

wait_idle() {  # prints the 1-min load at start and busy flag
  local t=0 l
  while :; do
    l=$(cut -d' ' -f1 /proc/loadavg)
    if awk -v l="$l" -v m="$LOADMAX" 'BEGIN{exit !(l < m)}'; then echo "$l 0"; return; fi
    if [ "$t" -ge "$WAITMAX" ]; then echo "$l 1"; return; fi
    sleep 10; t=$((t + 10))
  done
}

run_one() {  # code np rep
  local code=$1 np=$2 rep=$3 tag="$1.np$2.r$3" lw load busy
  lw=$(wait_idle); load=${lw% *}; busy=${lw#* }
  local log="$OUT/logs/$tag.out" tim="$OUT/logs/$tag.time"
  case $code in
    dem-bench)
      /usr/bin/time -v "$DEMBENCH" --steps 1000 --threads "$np" --json > "$log" 2> "$tim" ;;
    lammps_hertz_history|lammps_granular)
      /usr/bin/time -v mpirun --allow-run-as-root -np "$np" --bind-to core \
        lmp -in "$code.in" -log none -screen "$log" > /dev/null 2> "$tim" ;;
    liggghts_hertz)
      /usr/bin/time -v mpirun --allow-run-as-root -np "$np" --bind-to core \
        liggghts -in "$code.in" -log none -screen "$log" > /dev/null 2> "$tim" ;;
  esac
  local rss; rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$tim")
  python3 - "$code" "$np" "$rep" "$load" "$busy" "$rss" "$log" >> "$RES" <<'PY'
import json, re, sys
code, np, rep, load, busy, rss, log = sys.argv[1:8]
txt = open(log).read()
if code == 'dem-bench':
    j = json.loads(txt.strip().splitlines()[-1])
    loop, cpp = j['seconds'], j['contacts_per_particle']
else:
    part = txt.split('PEERBENCH timed')[1]
    loop = float(re.search(r'Loop time of ([0-9.eE+-]+)', part).group(1))
    chk = txt.split('PEERBENCH check')[1].split('\n')
    hdr = next(i for i, l in enumerate(chk) if l.split()[:2] == ['Step', 'Atoms'])
    cols = chk[hdr + 1].split()
    cpp = float(cols[-1])
    vmax, zmax = float(cols[3]), float(cols[4])
    if int(cols[1]) != 20000 or vmax > 0.05:
        sys.stderr.write('WARNING %s np%s: atoms %s vmax %g m/s zmax %g m\n' % (code, np, cols[1], vmax, zmax))
print('%s\t%s\t%s\t%s\t%s\t%.6g\t%.6g\t%.4g\t%s' % (code, np, rep, load, busy, loop, 20000 * 1000 / loop, cpp, rss))
PY
  tail -1 "$RES"
}

for rep in $(seq 1 "$REPS"); do
  for np in 1 2; do
    for code in dem-bench lammps_hertz_history lammps_granular liggghts_hertz; do
      run_one "$code" "$np" "$rep"
    done
  done
done

python3 - "$RES" <<'PY' | tee "$OUT/summary.txt"
import sys, statistics
rows = [l.rstrip('\n').split('\t') for l in open(sys.argv[1]) if not l.startswith('#')][1:]
print(open(sys.argv[1]).readline().strip()); print(open(sys.argv[1]).readlines()[1].strip())
print('| code | np | runs (particle-steps/s) | best | median | contacts/particle | max RSS (MB) | load1 at start |')
print('|---|---|---|---|---|---|---|---|')
keys = []
for r in rows:
    if (r[0], r[1]) not in keys: keys.append((r[0], r[1]))
for k in keys:
    rs = [r for r in rows if (r[0], r[1]) == k]
    p = [float(r[6]) for r in rs]
    print('| %s | %s | %s | %.3g | %.3g | %s | %s | %s |' % (
        k[0], k[1], ', '.join('%.3g' % x + ('*' if r[4] == '1' else '') for x, r in zip(p, rs)),
        max(p), statistics.median(p), '%.2f' % statistics.median([float(r[7]) for r in rs]),
        '%.1f' % (max(int(r[8]) for r in rs) / 1024), ', '.join(r[3] for r in rs)))
print('(* = started with load >= LOADMAX after waiting WAITMAX s)')
PY
