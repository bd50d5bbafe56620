#!/usr/bin/env bash
# Charts of the plastic and adhesive laws (issue 3, "Charts" and "Stability where methods
# fail"), at the reference case of the physics notes, with the parameter pool of
# scripts/jobs/10-single-contact.sh: ammonium fluorescein R = 2.45 um, rho = 1350 kg/m^3,
# E = 1.2 GPa, nu = 0.3, Gamma = 0.2 J/m^2, p_y = 35.3 MPa on silicon (E = 182 GPa, nu = 0.3;
# thesis Table 4.1); ke = 1500, kp = 210, kc = kcp = 20 N/m, f0 = 2.1 uN, f0p = 4.0 uN (thesis
# Table 4.2); Luding ke_max = 1500 N/m, phi_f = 0.02 (thesis 4.1.5); no viscous damping (e = 1).
# Exception: `nan` takes k_el, k_p, k_cl from its own correlations (eq 52, k_p = k_el, eq 38;
# physics notes) — with the Table 4.2 stiffnesses it sticks at 2, 5 and 10 m/s.
#
# Usage: bash scripts/jobs/20-epa-laws.sh BIN_DIR OUT_DIR      (about 15 s on 2 cores)
# Writes OUT_DIR/epa-laws/:
#   curves-LAW.png       impact force-overlap curves at 2, 5, 10 m/s (traces trace-LAW-vV.csv,
#                        summaries impact-LAW-vV.json), thornton-ning's dashed for comparison
#   e-v-all.png          e(v) of every law on one figure (e-v-LAW.csv / .h5), like thesis Fig 4.24
#   vys-py.png           V_ys, V_y0, V_y over V_s against p_y (second seed Fig 9, Table 5 set;
#                        vys-py.csv / .h5 from dem-nan)
#   cost-deviation.png   ns per force evaluation (dem-bench-contact) against the deviation from
#                        thornton-ning (cost-deviation.csv, cost-deviation.md)
#   nan-fig3.png         the nan law's oscillation without damping after yield and its
#                        suppression by beta_y = 0.1 (second seed Fig 3; nan-fig3-*.csv)
# Laws: every law of `dem-impact --list-laws` flagged [adhesive] or [plastic] (laws added later
# appear automatically); a law needing a coefficient outside the pool is skipped with a message.
#
# Deviation from thornton-ning (the nonlinear reference law), per law:
#   D_f = RMS over v = 2, 5, 10 m/s of D_f(v); D_f(v) = RMS over the points of the prescribed
#         quasi-static path 0 -> A(v) -> -0.2 A(v) (steps A/400; A = thornton-ning's alpha_max
#         in the impact at v) of (f_law - f_TN), over the points where either law is in
#         contact, divided by f_TN(A) (its force at the turning point);
#   D_e = RMS over v = 2, 5, 10 m/s of e_law(v) - e_TN(v) (absolute; impacts at dt factor 0.01).
set -euo pipefail
BIN=${1:?usage: $0 BIN_DIR OUT_DIR}
OUT=${2:?usage: $0 BIN_DIR OUT_DIR}/epa-laws
mkdir -p "$OUT"
IMPACT="$BIN/dem-impact"
CONTACT="$BIN/dem-contact"
NANTOOL="$BIN/dem-nan"
BENCH="$BIN/dem-bench-contact"
REF=thornton-ning
VELS=(2 5 10)

declare -A POOL=([E]=1.2e9 [nu]=0.3 [wall_E]=182e9 [wall_nu]=0.3 [gamma]=0.2 [py]=35.3e6
                 [kn]=1500 [ke]=1500 [kp]=210 [kc]=20 [kcp]=20 [f0]=2.1e-6 [f0p]=4.0e-6
                 [ke_max]=1500 [phi_f]=0.02 [e]=1)
SCENE=(--set R=2.45e-6 --set rho=1350 --set E=1.2e9 --set nu=0.3)

if gnuplot -e 'set terminal' 2>&1 | grep -q pngcairo; then
  TERM_PNG="pngcairo size 900,640 font ',11'"
  TERM_WIDE="pngcairo size 1400,560 font ',11'"
else
  TERM_PNG="png size 900,640"
  TERM_WIDE="png size 1400,560"
fi

"$IMPACT" --list-laws > "$OUT/laws.txt"
mapfile -t LAWS < <(awk -F'\t' '/^[^ ]/ && !/^scene keys/ && /\[(adhesive|plastic)\]/ {print $1}' \
  "$OUT/laws.txt")
echo "epa-laws: ${#LAWS[@]} plastic or adhesive laws: ${LAWS[*]}"

coef_keys() { # the coefficient keys of law $1
  awk -v L="$1" -F'\t' '/^[^ ]/ {cur = $1; next} cur == L {print $1}' "$OUT/laws.txt" |
    awk '{print $1}'
}
json_field() { # json_field FILE FIELD -> number
  grep -o "\"$2\":[^,}]*" "$1" | head -1 | cut -d: -f2 | tr -d ' '
}
law_args() { # the --set arguments of law $1
  local k
  for k in $(coef_keys "$1"); do
    case $k in E | nu) continue ;; esac
    if [ "$1" = nan ] && [[ $k == ke || $k == kp || $k == kc ]]; then continue; fi
    if [ -n "${POOL[$k]+x}" ]; then printf -- '--set\n%s=%s\n' "$k" "${POOL[$k]}"; fi
  done
}

# ---- impacts at 2, 5, 10 m/s and e(v) ---------------------------------------------------
ok_laws=()
for law in "${LAWS[@]}"; do
  mapfile -t LA < <(law_args "$law")
  ok=1
  for v in "${VELS[@]}"; do
    if ! "$IMPACT" --law "$law" "${SCENE[@]}" "${LA[@]}" --velocity "$v" --dt-factor 0.01 \
         --trace "$OUT/trace-$law-v$v.csv" --trace-every 4 --json \
         > "$OUT/impact-$law-v$v.json" 2> "$OUT/impact-$law-v$v.err"; then
      echo "epa-laws: skip '$law' (impact at $v m/s): $(cat "$OUT/impact-$law-v$v.err")"
      ok=0
      break
    fi
    rm -f "$OUT/impact-$law-v$v.err"
  done
  if [ $ok = 0 ]; then
    rm -f "$OUT"/impact-"$law"-v* "$OUT"/trace-"$law"-v*
    continue
  fi
  "$IMPACT" --law "$law" "${SCENE[@]}" "${LA[@]}" --sweep 0.3:50:36 --dt-factor 0.01 \
    --out "$OUT/e-v-$law.csv" > /dev/null
  "$IMPACT" --law "$law" "${SCENE[@]}" "${LA[@]}" --sweep 0.3:50:36 --dt-factor 0.01 \
    --out "$OUT/e-v-$law.h5" > /dev/null
  ok_laws+=("$law")
done
have_ref=0
for law in "${ok_laws[@]}"; do [ "$law" = "$REF" ] && have_ref=1; done

# Force-overlap curves, one figure per law (thornton-ning dashed for comparison).
for law in "${ok_laws[@]}"; do
  refplot=""
  if [ $have_ref = 1 ] && [ "$law" != "$REF" ]; then
    refplot=", for [v in \"2 5 10\"] '$OUT/trace-$REF-v'.v.'.csv' using (\$2*1e9):(\$5*1e6)"
    refplot+=" with lines dt 2 lw 1 lc rgb 'gray50'"
    refplot+=" title (v eq \"2\" ? \"$REF (2, 5, 10 m/s)\" : \"\")"
  fi
  titles=""
  for v in "${VELS[@]}"; do
    if grep -q '"stuck": *true' "$OUT/impact-$law-v$v.json"; then
      titles+="${titles:+, }\"$v m/s (sticks)\""
    else
      titles+="${titles:+, }\"$v m/s, e = $(awk -v e="$(json_field "$OUT/impact-$law-v$v.json" e)" \
        'BEGIN {printf "%.3f", e}')\""
    fi
  done
  gnuplot <<EOF
set terminal $TERM_PNG
set datafile separator ','
set grid
set key top left
array T[3] = [$titles]
set xlabel 'overlap alpha (nm)'
set ylabel 'normal force f_{el} (uN), > 0 repulsive'
set output '$OUT/curves-$law.png'
set title "$law: impact of a 2.45 um ammonium fluorescein sphere on silicon, no damping" noenhanced
plot for [i=1:3] '$OUT/trace-$law-v'.word("2 5 10", i).'.csv' using (\$2*1e9):(\$5*1e6) \
     with lines lw 2 lc i title T[i] $refplot
EOF
done

# e(v) of every law on one figure.
{
  echo "set terminal $TERM_PNG"
  echo "set datafile separator ','"
  echo "set grid; set logscale x; set key outside right top font ',10' noenhanced"
  echo "set xlabel 'impact velocity v (m/s)'; set ylabel 'coefficient of restitution e (-)'"
  echo "set yrange [0:1.05]; set xrange [0.3:50]"
  echo "set title 'e(v), 2.45 um ammonium fluorescein sphere on silicon, no damping (cf. thesis Fig 4.24)'"
  echo "set output '$OUT/e-v-all.png'"
  printf "plot "
  COLORS=("#9400d3" "#009e73" "#56b4e9" "#e69f00" "#e51e10" "#0072b2" "#808080" "#a0522d"
          "#ff69b4" "#2e8b57")
  i=0
  for law in "${ok_laws[@]}"; do
    [ $i -gt 0 ] && printf ", "
    style="lw 2 pt $((i + 4)) ps 0.8 lc rgb '${COLORS[i % 10]}'"
    [ "$law" = "$REF" ] && style="lw 4 pt 7 ps 0.8 lc rgb 'black'"
    printf "'%s' using 1:2 with linespoints %s title '%s'" "$OUT/e-v-$law.csv" "$style" "$law"
    i=$((i + 1))
  done
  echo
} > "$OUT/e-v-all.gp"
gnuplot "$OUT/e-v-all.gp"

# ---- V_ys(p_y), second seed Fig 9 (Table 5 set, Gamma = 0.24 J/m^2: docs/contact-laws.md) ---
T5=(--set R=2.45e-6 --set rho=1350 --set E=1.2e9 --set nu=0.33 --set wall_E=166e9
    --set wall_nu=0.28 --set gamma=0.24)
"$NANTOOL" "${T5[@]}" --py 5e6:120e6:200 --out "$OUT/vys-py.csv" 2> "$OUT/vys-py.log"
"$NANTOOL" "${T5[@]}" --py 5e6:120e6:200 --out "$OUT/vys-py.h5" 2> /dev/null
"$NANTOOL" "${T5[@]}" --py 5e6:120e6:2000 --json > "$OUT/vys-py.json" 2> /dev/null
PYC=$(json_field "$OUT/vys-py.json" py_crit)
PYS=$(json_field "$OUT/vys-py.json" py_vys_equals_vs)
VS=$(json_field "$OUT/vys-py.json" V_s)
gnuplot <<EOF
set terminal $TERM_PNG
set datafile separator ','
set grid
set logscale y
set xrange [0:120]
set yrange [0.01:40]
set xlabel 'yield contact pressure p_y (MPa)'
set ylabel 'velocity / V_s (-)'
set key top right
set title sprintf("nan law, 2.45 um ammonium fluorescein on silicon (paper Table 5), V_s = %.3f m/s", $VS)
set object 1 rect from 0, graph 0 to $PYC/1e6, graph 1 fc rgb '#dddddd' fs solid 0.5 noborder behind
set label 1 sprintf("adhesion-induced yield\n(V_y^2 < 0), p_y < %.1f MPa", $PYC/1e6) at 8, 0.03 front
set arrow 1 from $PYS/1e6, graph 0 to $PYS/1e6, graph 1 nohead dt 3 lc rgb 'gray30'
set label 2 sprintf("V_{ys} = V_s from %.1f MPa", $PYS/1e6) at $PYS/1e6 + 2, 0.4
set output '$OUT/vys-py.png'
plot '$OUT/vys-py.csv' using (\$1/1e6):(\$5/\$2) with lines lw 3 title 'V_{ys} / V_s (eqs 77-79)', \
     '' using (\$1/1e6):(\$3/\$2) with lines lw 2 dt 2 title 'V_{y0} / V_s (eq 74)', \
     '' using (\$1/1e6):(\$4 > 0 ? \$4/\$2 : NaN) with lines lw 2 dt 4 title 'V_y / V_s (eq 75)', \
     1 with lines lw 1 lc rgb 'black' title 'V_s (eq 73)'
EOF

# ---- cost per evaluation against the deviation from thornton-ning ---------------------------
if [ $have_ref = 1 ]; then
  "$BENCH" --json --time 0.1 --repeats 9 > "$OUT/bench-contact.json"
  ns_of() { # ns_best of row $1 (the JSON is indented one field a line; no jq needed)
    awk -v n="$1" -F'"' '$2 == "name" {cur = $4} $2 == "ns_best" && cur == n {
      sub(/.*: */, ""); sub(/,.*/, ""); print; exit }' "$OUT/bench-contact.json"
  }
  base=$(ns_of baseline)
  echo "law,cost [ns],ns_best [ns],D_f(2),D_f(5),D_f(10),D_f,e(2),e(5),e(10),D_e" \
    > "$OUT/cost-deviation.csv"
  for law in "${ok_laws[@]}"; do
    mapfile -t LA < <(law_args "$law")
    row="$law"
    dfs=()
    for v in "${VELS[@]}"; do
      A=$(json_field "$OUT/impact-$REF-v$v.json" alpha_max)
      path=$(awk -v a="$A" 'BEGIN {printf "0,%.9e,%.9e", a, -0.2*a}')
      step=$(awk -v a="$A" 'BEGIN {printf "%.9e", a/400}')
      "$CONTACT" --law "$law" "${SCENE[@]}" "${LA[@]}" --path "$path" --step "$step" \
        --out "$OUT/path-$law-v$v.csv" > /dev/null
      if [ "$law" = "$REF" ]; then dfs+=(0); continue; fi
      mapfile -t LR < <(law_args "$REF")
      [ -e "$OUT/path-$REF-v$v.csv" ] ||
        "$CONTACT" --law "$REF" "${SCENE[@]}" "${LR[@]}" --path "$path" --step "$step" \
          --out "$OUT/path-$REF-v$v.csv" > /dev/null
      # Rows align (same path and step); columns alpha,f,f_el,k,f_adh,contact.
      d=$(paste -d, <(grep -v '^#' "$OUT/path-$law-v$v.csv" | tail -n +2) \
                    <(grep -v '^#' "$OUT/path-$REF-v$v.csv" | tail -n +2) |
        awk -F, '
          { if ($1 != $7) { print "misaligned" > "/dev/stderr"; exit 1 }
            if ($6 + $12 > 0) { s += ($2 - $8)^2; n++ }
            if ($8 > fA) fA = $8 }
          END { printf "%.6g", sqrt(s / n) / fA }')
      dfs+=("$d")
    done
    es=()
    for v in "${VELS[@]}"; do es+=("$(json_field "$OUT/impact-$law-v$v.json" e)"); done
    ers=()
    for v in "${VELS[@]}"; do ers+=("$(json_field "$OUT/impact-$REF-v$v.json" e)"); done
    ns=$(ns_of "$law")
    awk -v law="$law" -v ns="$ns" -v b="$base" -v d1="${dfs[0]}" -v d2="${dfs[1]}" \
        -v d3="${dfs[2]}" -v e1="${es[0]}" -v e2="${es[1]}" -v e3="${es[2]}" \
        -v r1="${ers[0]}" -v r2="${ers[1]}" -v r3="${ers[2]}" 'BEGIN {
      df = sqrt((d1^2 + d2^2 + d3^2) / 3)
      de = sqrt(((e1 - r1)^2 + (e2 - r2)^2 + (e3 - r3)^2) / 3)
      printf "%s,%.3g,%.3g,%.4g,%.4g,%.4g,%.4g,%.4f,%.4f,%.4f,%.4g\n",
             law, ns - b, ns, d1, d2, d3, df, e1, e2, e3, de }' >> "$OUT/cost-deviation.csv"
  done
  {
    echo "| law | cost (ns/eval, best - baseline) | D_f(2) | D_f(5) | D_f(10) | D_f | e(2) | e(5) | e(10) | D_e |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    tail -n +2 "$OUT/cost-deviation.csv" | awk -F, '{printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $4, $5, $6, $7, $8, $9, $10, $11}'
    echo
    echo "baseline (harness + indirect call) $base ns; machine: $(grep -o '"cpu": *"[^"]*"' "$OUT/bench-contact.json" | cut -d'"' -f4), gcc $(grep -o '"compiler": *"[^"]*"' "$OUT/bench-contact.json" | cut -d'"' -f4)"
  } > "$OUT/cost-deviation.md"
  # One point per law with its own symbol and a legend (labels would overlap); the reference
  # (D = 0) is the vertical line at its cost; log scales.
  names=$(tail -n +2 "$OUT/cost-deviation.csv" | cut -d, -f1 | grep -vx "$REF" | tr '\n' ' ')
  nrow=$(wc -w <<< "$names")
  refcost=$(awk -F, -v r="$REF" '$1 == r {print $2}' "$OUT/cost-deviation.csv")
  gnuplot <<EOF
set terminal $TERM_WIDE
set datafile separator ','
set grid
set logscale xy
set xrange [0.3:1000]
set yrange [0.005:5]
set output '$OUT/cost-deviation.png'
set multiplot layout 1,2 title 'Cost of one force evaluation vs deviation from $REF (reference case, 2, 5, 10 m/s); dashed: $REF itself' noenhanced
set xlabel 'cost per evaluation, best of 9 minus baseline (ns; below 0.3 drawn at 0.3)'
set arrow 1 from $refcost, graph 0 to $refcost, graph 1 nohead dt 2 lw 2 lc rgb 'black'
names = "$names"
sel(c) = (c > 0.3 ? c : 0.3)
set key off
set ylabel 'D_f: RMS force difference on the path / f_{TN}(alpha_{max}) (-)'
set title 'force-overlap curve'
plot for [i=1:$nrow] '$OUT/cost-deviation.csv' using (strcol(1) eq word(names, i) ? sel(\$2) : NaN):7 \
     with points pt (i + 3) ps 2.2 lw 2 title word(names, i) noenhanced
set key outside right top noenhanced
set ylabel 'D_e: RMS of e - e_{TN} over 2, 5, 10 m/s (-)'
set title 'coefficient of restitution'
plot for [i=1:$nrow] '$OUT/cost-deviation.csv' using (strcol(1) eq word(names, i) ? sel(\$2) : NaN):11 \
     with points pt (i + 3) ps 2.2 lw 2 title word(names, i)
unset multiplot
EOF
else
  echo "epa-laws: no '$REF' law: cost-deviation chart skipped"
fi

# ---- nan, second seed Fig 3: no damping after yield oscillates; beta_y = 0.1 damps it ------
# Table 5 set at p_y = 30 MPa, impact at 1 m/s (below V_ys = 1.86 m/s: the particle sticks),
# e0 = 0.81 with beta = 1 before yield (tests/check_energy_nan_tn.c uses the same scene).
for by in 0 0.1; do
  "$IMPACT" --law nan "${T5[@]}" --set py=30e6 --set e=0.81 --set beta=1 --set beta_y=$by \
    --velocity 1 --t-max-factor 60 --trace "$OUT/nan-fig3-beta_y$by.csv" --trace-every 10 \
    --json > "$OUT/nan-fig3-beta_y$by.json"
done
gnuplot <<EOF
set terminal $TERM_WIDE
set datafile separator ','
set grid
set output '$OUT/nan-fig3.png'
set multiplot layout 1,2 title 'nan law, 2.45 um ammonium fluorescein on silicon at 1 m/s (p_y = 30 MPa, e_0 = 0.81, beta = 1 before yield): second seed Fig 3' noenhanced
set xlabel 'time t (us)'
set ylabel 'normal force f (uN), > 0 repulsive'
set key top right
set yrange [-5:7.5]
set title 'force against time'
plot '$OUT/nan-fig3-beta_y0.csv' using (\$1*1e6):(\$4*1e6) with lines lw 1 lc rgb 'red' title 'beta_y = 0 (no damping after yield)', \
     '$OUT/nan-fig3-beta_y0.1.csv' using (\$1*1e6):(\$4*1e6) with lines lw 2 lc rgb 'blue' title 'beta_y = 0.1'
set xlabel 'overlap alpha (nm)'
set ylabel 'elastic-plastic force f_{el} (uN)'
set key bottom right
set yrange [-5:5]
set title 'force against overlap'
plot '$OUT/nan-fig3-beta_y0.csv' using (\$2*1e9):(\$5*1e6) with lines lw 1 lc rgb 'red' title 'beta_y = 0', \
     '$OUT/nan-fig3-beta_y0.1.csv' using (\$2*1e9):(\$5*1e6) with lines lw 2 lc rgb 'blue' title 'beta_y = 0.1'
unset multiplot
EOF
echo "epa-laws: results in $OUT"
