#!/usr/bin/env python3
"""Re-reference the stored full-tier runs of 2026-12-01 (made before the bed-surface fix)
to the fixed surface, as entries of dem-validate's run cache, so that dem-validate itself
evaluates every criterion on them (README.md in this folder says what this is and is not).

  reanalyse.py DEM_VALIDATE SURFACE_SHIFT BEDS_DIR OUTDIR[:LOG] ...

For every OUTDIR (an earlier `dem-validate --out`) and its progress LOG (stderr of that
invocation), each run "run N: <label>" is bound to the bed of the last "bed NAME:" line
before it, its series OUTDIR/data/run_NN.dat is read (h/r, H, bin p, bin q, bin phi, base p,
F), and with z_old, z_new the surface under its footprint (r_foot = D/2) by the selection
the run used and by the fixed one (SURFACE_SHIFT), the depth becomes
h_new = h_old + (z_new - z_old), H = F / A(h_new) (sphere pi (D h - h^2), flat cylinder
pi D^2 / 4, cube D^2), h/r = h_new / r. The entry is written in the cache format of
validate/cache.c with the hash of DEM_VALIDATE, the bed file's stamp and status 0; the
base stress before contact (base_p0, not stored in the data files) is taken as the first
stored sample's. Runs already in the cache (e.g. made by the fixed program) are left alone.
"""
import math
import os
import re
import subprocess
import sys

MAGIC = "# dem-validate run cache, format 1"


def fnv1a64(path):
    h = 1469598103934665603
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 16), b""):
            for b in chunk:
                h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


def stamp(path):
    st = os.stat(path)
    return "%d.%09d:%d" % (st.st_mtime_ns // 10**9, st.st_mtime_ns % 10**9, st.st_size)


def area(shape, D, h):
    if shape == "cube":
        return D * D
    if shape == "cylinder" or h >= 0.5 * D:
        return 0.25 * math.pi * D * D
    return math.pi * (D * h - h * h) if h > 0 else 0.0


RUN = re.compile(r"\] run (\d+): bed ([\d.]+) d, (sphere|cylinder|cube) ([\d.]+) d, gamma\* ([\d.e+-]+), "
                 r"kn x([\d.e+-]+), mu_i ([\d.e+-]+), dt x([\d.e+-]+)(, k x[\d.e+-]+)?$")
DONE = re.compile(r"\] run (\d+): (\d+) samples .*, ([\d.]+) s, (\d+) steps$")
BED = re.compile(r"\] bed (bed\S+): ")


def main():
    exe, shift, beds = sys.argv[1:4]
    code = fnv1a64(exe)
    hend = 0.5  # the full tier's h/r at the end (validate/run.c)
    made = kept = 0
    for arg in sys.argv[4:]:
        out, log = arg.split(":") if ":" in arg else (arg, arg + ".log")
        cur, runs, done = None, {}, {}
        for line in open(log):
            line = line.rstrip("\n")
            m = BED.search(line)
            if m:
                cur = m.group(1).rstrip(":")
            m = RUN.search(line)
            if m:
                runs[int(m.group(1))] = (cur, m.groups())
            m = DONE.search(line)
            if m:
                done[int(m.group(1))] = (float(m.group(3)), int(m.group(4)))
        for n, (bed, g) in sorted(runs.items()):
            if n not in done:
                continue  # failed or interrupted
            _, hb, shape, D, gs, kn, mui, dts, _k = g
            if not bed.startswith("bed%s_" % hb):
                sys.exit("%s run %d: label bed %s d but last bed line %s" % (log, n, hb, bed))
            D = float(D)
            key = "%s__%s%g_g%g_kn%g_mui%g_dts%g_h%g" % (bed, shape, D, float(gs), float(kn),
                                                        float(mui), float(dts), hend)
            path = os.path.join(beds, "run_%s.dat" % key)
            bedfile = os.path.join(beds, bed + ".h5")
            if os.path.exists(path):
                kept += 1
                continue
            r_d = 0.5 * D
            zo, zn, so, sn = map(float, subprocess.check_output(
                [shift, bedfile, "%g" % r_d], text=True).split()[1:])
            rad = 0.5 * D * 1e-3
            rows = [list(map(float, l.split())) for l in open(os.path.join(out, "data", "run_%02d.dat" % n))
                    if l.strip() and not l.startswith("#")]
            new = []
            for hr, _H, bp, bq, bphi, base, F in rows:
                h = hr * rad + (zn - zo)
                if h <= 0:
                    continue
                new.append((h / rad, F / area(shape, D * 1e-3, h), bp, bq, bphi, base, F))
            wall, steps = done[n]
            tmp = path + ".tmp"
            with open(tmp, "w") as f:
                f.write("%s\n# code %s\n# bed_file %s\n# label reanalysed from %s run %d\n"
                        "# status 0\n# wall_s %.17g\n# threads 2\n# steps %d\n# dt 0\n"
                        "# surface %.17g\n# surface_sd %.17g\n# max_overlap 0\n# base_p0 %.17g\n"
                        "# have_stress 1\n# samples %d\n# columns h/r H[Pa] bin_p[Pa] bin_q[Pa] "
                        "bin_phi base_p[Pa] F[N]\n" % (MAGIC, code, stamp(bedfile), out, n, wall,
                                                       steps, zn, sn, rows[0][5], len(new)))
                for row in new:
                    f.write(" ".join("%.17g" % v for v in row) + "\n")
            os.rename(tmp, path)
            made += 1
            print("%-78s dz %+.3f d  (%s run %d)" % (key[:78], (zn - zo) * 1e3, out, n))
    print("%d entries written, %d already in the cache" % (made, kept))


if __name__ == "__main__":
    main()
