/* report.c — the report of a validation run: report.md and report.html (one content, two
 * renderings), summary.json, per-run data files and gnuplot PNG figures in the out folder.
 * Every file is written to a temporary name and renamed. */
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "dem/table.h"
#include "vh.h"

/* ---- a document written as Markdown and HTML at once ---------------------------------- */
typedef struct doc {
  FILE *md, *html;
} doc;

static void esc(FILE *f, const char *s) {
  for (; *s; s++) {
    if (*s == '<') fputs("&lt;", f);
    else if (*s == '>') fputs("&gt;", f);
    else if (*s == '&') fputs("&amp;", f);
    else fputc(*s, f);
  }
}

static void d_head(doc *d, int level, const char *fmt, ...) {
  char b[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(b, sizeof b, fmt, ap);
  va_end(ap);
  fprintf(d->md, "\n%.*s %s\n\n", level, "######", b);
  fprintf(d->html, "<h%d>", level);
  esc(d->html, b);
  fprintf(d->html, "</h%d>\n", level);
}

static void d_para(doc *d, const char *fmt, ...) {
  char b[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(b, sizeof b, fmt, ap);
  va_end(ap);
  fprintf(d->md, "%s\n\n", b);
  fputs("<p>", d->html);
  esc(d->html, b);
  fputs("</p>\n", d->html);
}

static void d_row(doc *d, int header, int n, const char *const *cells) {
  fputc('|', d->md);
  fputs("<tr>", d->html);
  for (int i = 0; i < n; i++) {
    /* a '|' inside a cell would split the Markdown row */
    fputc(' ', d->md);
    for (const char *s = cells[i]; *s; s++) fputc(*s == '|' ? '/' : *s, d->md);
    fputs(" |", d->md);
    fputs(header ? "<th>" : "<td>", d->html);
    esc(d->html, cells[i]);
    fputs(header ? "</th>" : "</td>", d->html);
  }
  fputs("\n", d->md);
  fputs("</tr>\n", d->html);
  if (header) {
    fputc('|', d->md);
    for (int i = 0; i < n; i++) fputs("---|", d->md);
    fputc('\n', d->md);
  }
}
static void d_table_begin(doc *d) { fputs("<table>\n", d->html); }
static void d_table_end(doc *d) {
  fputs("\n", d->md);
  fputs("</table>\n", d->html);
}
static void d_img(doc *d, const char *file, const char *alt) {
  fprintf(d->md, "![%s](%s)\n\n", alt, file);
  fprintf(d->html, "<p><img src=\"%s\" alt=\"", file);
  esc(d->html, alt);
  fputs("\" width=\"720\"></p>\n", d->html);
}

/* ---- files ----------------------------------------------------------------------------- */
static FILE *open_tmp(const char *dir, const char *name, char *tmp, size_t len) {
  snprintf(tmp, len, "%s/.%s.tmp%ld", dir, name, (long)getpid());
  return fopen(tmp, "w");
}
static int close_rename(FILE *f, const char *tmp, const char *dir, const char *name,
                        dem_err *err) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  int bad = ferror(f);
  if (fclose(f) || bad || rename(tmp, path)) {
    remove(tmp);
    return dem_err_set(err, DEM_EIO, "dem-validate: cannot write %s", path);
  }
  return DEM_OK;
}

/* data/run_NN.dat: h/r, H [Pa], bin p, bin q, bin phi, base p [Pa], F [N], then the
 * footprint of the indenter's contacts: a_c [d], Hc = F / (pi a_c^2) [Pa], a_c^2 / (D h - h^2)
 * (spheres; NaN otherwise), indenter contacts. */
static int write_run_data(const vh *h, int i, dem_err *err) {
  char dir[600], name[64], tmp[800];
  snprintf(dir, sizeof dir, "%s/data", h->out);
  snprintf(name, sizeof name, "run_%02d.dat", i);
  FILE *f = open_tmp(dir, name, tmp, sizeof tmp);
  if (!f) return dem_err_set(err, DEM_EIO, "dem-validate: cannot write %s/%s", dir, name);
  const vh_run *r = &h->runs[i];
  fprintf(f, "# %s\n# h/r  H[Pa]  bin_p[Pa]  bin_q[Pa]  bin_phi  base_p[Pa]  F[N]  a_c[d]  "
             "Hc[Pa]  a_c^2/(Dh-h^2)  indenter_contacts\n", r->label);
  for (size_t k = 0; k < r->n; k++) {
    const double ratio = vh_footprint_ratio(r, k);
    fprintf(f, "%.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g\n", r->hr[k], r->H[k],
            r->bin_p[k], r->bin_q[k], r->bin_phi[k], r->base_p[k], r->F[k], r->ac[k] / D_MEAN,
            r->Hc[k], ratio, r->nind[k]);
  }
  return close_rename(f, tmp, dir, name, err);
}

static int have_gnuplot(void) { return system("command -v gnuplot >/dev/null 2>&1") == 0; }

static int gnuplot(const vh *h, const char *script, dem_err *err) {
  char tmp[800];
  FILE *f = open_tmp(h->out, "plot.gp", tmp, sizeof tmp);
  if (!f) return dem_err_set(err, DEM_EIO, "dem-validate: cannot write a gnuplot script");
  fputs(script, f);
  fclose(f);
  /* gnuplot runs in the out folder (the script names the data and PNG files relative to
   * it), so it is given the script's name there: tmp is "OUT/name", and a relative OUT
   * (the default, and the main job's) would not be found from inside OUT */
  const char *base = strrchr(tmp, '/');
  base = base ? base + 1 : tmp;
  char cmd[1800];
  snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot '%s' 2>/dev/null", h->out, base);
  int rc = system(cmd);
  remove(tmp);
  return rc == 0 ? DEM_OK : dem_err_set(err, DEM_EIO, "dem-validate: gnuplot failed");
}

#define HEAD                                                                                 \
  "set terminal pngcairo size 900,560 font ',11'\nset grid\nset key outside right top\n"

/* H (column 2, kPa) or a stress column against h/r for the case's runs. */
int vh_plot_runs(const vh *h, const char *png, const char *title, const int *runs, int nruns,
                 const char *const *labels, int column, dem_err *err) {
  char s[8192];
  size_t m = (size_t)snprintf(s, sizeof s, HEAD "set output '%s'\nset title \"%s\"\n"
                                           "set xlabel 'h/r'\nset xrange [0:*]\n",
                              png, title);
  const char *yl = column == 2   ? "H [kPa]"
                   : column == 5 ? "solids fraction of the dynamic bin"
                   : column == 9 ? "Hc = F / (pi a_c^2) [kPa]"
                                 : "stress [kPa]";
  /* the first samples (a few particles under a vanishing area) reach tens of times the
   * plateau: show the plateau, as the thesis' figures do (they start at one diameter) */
  double top = 0;
  for (int i = 0; i < nruns; i++) {
    const vh_run *r = &h->runs[runs[i]];
    double v = column == 2 ? r->sH.mean : column == 3 ? r->sp.mean
                                         : column == 9 ? r->sHc.mean : NAN;
    if (isfinite(v) && v > top) top = v;
  }
  if (top > 0) m += (size_t)snprintf(s + m, sizeof s - m, "set yrange [0:%g]\n", 2.5 * top / 1e3);
  m += (size_t)snprintf(s + m, sizeof s - m, "set ylabel '%s'\nplot ", yl);
  /* A run on a replicate bed ("label, seed s") takes the colour of its first bed's run
   * ("label") and dash type s, so the beds of one variant read as one colour. */
  int colour[VH_MAX_CASE_RUNS], ncol = 0;
  for (int i = 0; i < nruns && i < VH_MAX_CASE_RUNS && m < sizeof s - 256; i++) {
    const char *scale = column == 5 ? "" : "/1000";
    const char *sd = strstr(labels[i], ", seed ");
    int dash = 1;
    colour[i] = 0;
    if (sd) {
      size_t base = (size_t)(sd - labels[i]);
      dash = atoi(sd + 7);
      dash = dash < 1 ? 1 : dash > 5 ? 5 : dash;
      for (int j = 0; j < i; j++)
        if (strncmp(labels[j], labels[i], base) == 0 && labels[j][base] == 0) {
          colour[i] = colour[j];
          break;
        }
    }
    if (!colour[i]) colour[i] = ++ncol;
    m += (size_t)snprintf(s + m, sizeof s - m, "%s'data/run_%02d.dat' u 1:($%d%s) w l lw 1.5 "
                                               "lc %d dt %d t \"%s\"",
                          i ? ", " : "", runs[i], column, scale, colour[i], dash,
                          labels[i]);
  }
  snprintf(s + m, sizeof s - m, "\n");
  return gnuplot(h, s, err);
}

/* Plateau mean with sd bars (the thesis' fluctuation bars) against the varied parameter. */
int vh_plot_trend(const vh *h, const char *png, const char *title, const char *xlabel,
                  const double *x, const int *runs, int nruns, int logx, dem_err *err) {
  char dat[64], tmp[800];
  snprintf(dat, sizeof dat, "%.40s.dat", png);
  FILE *f = open_tmp(h->out, dat, tmp, sizeof tmp);
  if (!f) return dem_err_set(err, DEM_EIO, "dem-validate: cannot write %s", dat);
  fprintf(f, "# x  H_mean[Pa]  H_sd  H_se  p_mean  p_sd  q_mean  q_sd\n");
  for (int i = 0; i < nruns; i++) {
    const vh_run *r = &h->runs[runs[i]];
    if (!isfinite(x[i]) || r->status) continue;
    fprintf(f, "%.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g\n", x[i], r->sH.mean, r->sH.sd,
            r->sH.se, r->sp.mean, r->sp.sd, r->sq.mean, r->sq.sd);
  }
  int rc = close_rename(f, tmp, h->out, dat, err);
  if (rc) return rc;
  char s[2048];
  snprintf(s, sizeof s,
           HEAD "set output '%s'\nset title \"%s\"\nset xlabel \"%s\"\nset ylabel 'kPa'\n%s"
                "set offsets graph 0.05, graph 0.05, 0, 0\n"
                "plot '%s' u 1:($2/1000):($3/1000) w yerrorlines lw 2 t 'H (bars: sd)', "
                "'' u 1:($5/1000):($6/1000) w yerrorlines t 'dynamic bin hydrostatic', "
                "'' u 1:($7/1000):($8/1000) w yerrorlines t 'dynamic bin deviatoric'\n",
           png, title, xlabel, logx ? "set logscale x\n" : "", dat);
  return gnuplot(h, s, err);
}

/* Case 10's dynamic-pressure reading (cases.c rate_fit): H with its standard error against
 * rho_b v^2, and the fitted line H0 + beta rho_b v^2. */
static int plot_rate_fit(const vh *h, const vh_case_result *r, const char *png, dem_err *err) {
  char dat[64], tmp[800];
  snprintf(dat, sizeof dat, "%.40s.dat", png);
  FILE *f = open_tmp(h->out, dat, tmp, sizeof tmp);
  if (!f) return dem_err_set(err, DEM_EIO, "dem-validate: cannot write %s", dat);
  fprintf(f, "# gamma*  v[m/s]  rho_b_v2[Pa]  H_mean[Pa]  H_se[Pa]  H_sd[Pa]  (rho_b = %.6g "
             "kg/m^3)\n", r->rho_b);
  for (int i = 0; i < r->nruns; i++) {
    const vh_run *u = &h->runs[r->runs[i]];
    if (u->status || !isfinite(u->v) || !isfinite(u->sH.mean)) continue;
    /* every replicate bed's runs (their x is NaN but for the first bed's) */
    fprintf(f, "%.6g %.6g %.6g %.6g %.6g %.6g\n", u->ind.gamma_star, u->v, r->rho_b * u->v * u->v,
            u->sH.mean, u->sH.se, u->sH.sd);
  }
  int rc = close_rename(f, tmp, h->out, dat, err);
  if (rc) return rc;
  const dem_rate_fit *q = &r->rate_fit;
  char s[2048];
  snprintf(s, sizeof s,
           HEAD "set output '%s'\nset title \"%s: H against the dynamic pressure\"\n"
                "set xlabel 'rho_b v^2 [kPa] (rho_b = %.0f kg/m^3)'\nset ylabel 'H [kPa]'\n"
                "set logscale x\nset offsets graph 0.05, graph 0.05, 0, 0\n"
                "f(x) = %.9g + %.9g * x\n"
                "plot '%s' u ($3/1000):($4/1000):($5/1000) w yerrorbars pt 7 lw 2 "
                "t 'plateau H (bars: standard error)', "
                "'' u ($3/1000):($4/1000):(sprintf('%%g', $1)) w labels offset 1.5,1 notitle, "
                "f(x) w l lw 1.5 t 'fit: H0 %.2f kPa + %.2f rho_b v^2'\n",
           png, r->title, r->rho_b, q->H0 / 1e3, q->beta, dat, q->H0 / 1e3, q->beta);
  return gnuplot(h, s, err);
}

static void case_plots(vh *h, vh_case_result *r, int plots, dem_err *err) {
  if (!plots || r->nruns == 0) return;
  const char *labels[VH_MAX_CASE_RUNS];
  int runs[VH_MAX_CASE_RUNS], n = 0;
  for (int i = 0; i < r->nruns; i++)
    if (h->runs[r->runs[i]].status == DEM_OK && h->runs[r->runs[i]].n > 0)
      runs[n] = r->runs[i], labels[n++] = r->labels[i];
  if (!n) return;
  int k = 0;
  char png[96], title[160];
  snprintf(png, sizeof png, "%s_H.png", r->name);
  snprintf(title, sizeof title, "%s: hardness", r->title);
  if (!vh_plot_runs(h, png, title, runs, n, labels, 2, err)) snprintf(r->plots[k++], 96, "%s", png);
  int stress = 0;
  for (int i = 0; i < n; i++) stress |= h->runs[runs[i]].have_stress;
  if (stress) {
    snprintf(png, sizeof png, "%s_p.png", r->name);
    snprintf(title, sizeof title, "%s: hydrostatic stress in the dynamic bin", r->title);
    if (!vh_plot_runs(h, png, title, runs, n, labels, 3, err))
      snprintf(r->plots[k++], 96, "%s", png);
    if (strcmp(r->name, "bed-height") == 0) {
      /* the static bin at the base (thesis Figs 5.13-5.14: whether the indentation reaches
       * the base of the die) */
      snprintf(png, sizeof png, "%s_base.png", r->name);
      snprintf(title, sizeof title, "%s: hydrostatic stress in the static bin at the base",
               r->title);
      if (!vh_plot_runs(h, png, title, runs, n, labels, 6, err))
        snprintf(r->plots[k++], 96, "%s", png);
    }
    if (strcmp(r->name, "indenter-shape") == 0) {
      snprintf(png, sizeof png, "%s_phi.png", r->name);
      snprintf(title, sizeof title, "%s: solids fraction of the dynamic bin", r->title);
      if (!vh_plot_runs(h, png, title, runs, n, labels, 5, err))
        snprintf(r->plots[k++], 96, "%s", png);
    }
  }
  if (r->xlabel) {
    snprintf(png, sizeof png, "%s_trend.png", r->name);
    snprintf(title, sizeof title, "%s: plateau means", r->title);
    if (!vh_plot_trend(h, png, title, r->xlabel, r->x, r->runs, r->nruns, r->logx, err))
      snprintf(r->plots[k++], 96, "%s", png);
  }
  /* the mean pressure on the contacts' own footprint (docs/analysis.md 2b), for the cases
   * whose reading depends on the contact area: the plateau's shape, the shallow bed and the
   * large balls */
  const int foot = !strcmp(r->name, "plateau") || !strcmp(r->name, "bed-height") ||
                   !strcmp(r->name, "indenter-size");
  int have_foot = 0;
  for (int i = 0; i < n; i++) have_foot |= isfinite(h->runs[runs[i]].sHc.mean);
  if (foot && have_foot && k < 5) {
    snprintf(png, sizeof png, "%s_Hc.png", r->name);
    snprintf(title, sizeof title, "%s: mean pressure on the contacts' footprint", r->title);
    if (!vh_plot_runs(h, png, title, runs, n, labels, 9, err))
      snprintf(r->plots[k++], 96, "%s", png);
  }
  if (r->has_rate_fit && k < 5) {
    snprintf(png, sizeof png, "%s_dynamic.png", r->name);
    if (!plot_rate_fit(h, r, png, err)) snprintf(r->plots[k++], 96, "%s", png);
  }
  /* a figure that could not be made is said, not silently left out of the report */
  if (err->code) vh_log(h, "warning: case %s: %s (a figure is missing from the report)",
                        r->name, err->msg);
  *err = (dem_err){0};
}

/* Copy src to dir/name (through a temporary file). 0 or -1. */
static int copy_file(const char *src, const char *dir, const char *name) {
  char dst[800], tmp[820];
  snprintf(dst, sizeof dst, "%s/%s", dir, name);
  snprintf(tmp, sizeof tmp, "%s.tmp%ld", dst, (long)getpid());
  FILE *in = fopen(src, "rb");
  if (!in) return -1;
  FILE *out = fopen(tmp, "wb");
  if (!out) {
    fclose(in);
    return -1;
  }
  char buf[65536];
  size_t m;
  int bad = 0;
  while ((m = fread(buf, 1, sizeof buf, in)) > 0)
    if (fwrite(buf, 1, m, out) != m) bad = 1;
  bad |= ferror(in);
  fclose(in);
  if (fclose(out) || bad || rename(tmp, dst)) {
    remove(tmp);
    return -1;
  }
  return 0;
}

static void machine(char *b, size_t n) {
  struct utsname u;
  long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  if (uname(&u) == 0)
    snprintf(b, n, "%s %s %s, %ld cores", u.nodename, u.sysname, u.release, cpus);
  else
    snprintf(b, n, "%ld cores", cpus);
}

/* The statistics of a run, or none (NaN: "-" in the tables, null in the JSON) for a run
 * that failed or was not made: its zeroed fields are not a hardness of 0. */
static dem_series_stats run_stats_of(const vh_run *u, const dem_series_stats *s) {
  if (u->status == DEM_OK) return *s;
  dem_series_stats none;
  memset(&none, 0, sizeof none);
  none.mean = none.se = none.sd = none.slope = none.n_eff = NAN;
  return none;
}

static void fmt_stats(char *b, size_t n, const dem_series_stats *s, double scale) {
  if (isfinite(s->mean))
    snprintf(b, n, "%.3g +- %.2g", s->mean * scale, s->se * scale);
  else
    snprintf(b, n, "-");
}

int vh_report_write(const vh *h, const vh_case_result *cres, int nres, double wall_s,
                    dem_err *err) {
  vh_case_result *res = (vh_case_result *)cres;
  char dir[600];
  snprintf(dir, sizeof dir, "%s/data", h->out);
  int rc;
  if ((rc = dem_mkdirs(dir, err))) {
    dem_err_prefix(err, "dem-validate: ");
    return rc;
  }
  for (int i = 0; i < h->nruns; i++)
    if (h->runs[i].status == DEM_OK && (rc = write_run_data(h, i, err))) return rc;
  int plots = have_gnuplot();
  for (int i = 0; i < nres; i++) case_plots((vh *)h, &res[i], plots, err);

  char tmd[800], thtml[800];
  doc d = {open_tmp(h->out, "report.md", tmd, sizeof tmd),
           open_tmp(h->out, "report.html", thtml, sizeof thtml)};
  if (!d.md || !d.html) {
    if (d.md) fclose(d.md), remove(tmd);
    if (d.html) fclose(d.html), remove(thtml);
    return dem_err_set(err, DEM_EIO, "dem-validate: cannot write the report in %s", h->out);
  }
  fputs("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>DEM validation report"
        "</title><style>body{font-family:sans-serif;max-width:1100px;margin:auto}"
        "table{border-collapse:collapse}td,th{border:1px solid #999;padding:3px 6px;"
        "font-size:90%}</style></head><body>\n",
        d.html);
  const vh_tier *t = h->tier;
  char mach[256], when[64];
  machine(mach, sizeof mach);
  time_t now = time(NULL);
  strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", gmtime(&now));
  int npass = 0, nfail = 0, nother = 0;
  for (int i = 0; i < nres; i++) {
    if (res[i].status == VH_PASS) npass++;
    else if (res[i].status == VH_FAIL) nfail++;
    else nother++;
  }
  double cost = 0;
  int ncached = 0;
  for (int i = 0; i < nres; i++) cost += res[i].cost_s;
  for (int i = 0; i < h->nruns; i++) ncached += h->runs[i].cached;
  d_head(&d, 1, "Ball-indentation validation report (tier %s)", t->name);
  d_para(&d, "%s on %s, %d MPI rank(s) x %d threads; wall time %.0f s (%.1f min). The beds "
             "and runs took %.0f s (%.1f min) when they were made (%d of %d runs from the "
             "run cache). Cases: %d PASS, %d FAIL, %d "
             "other. Produced by `dem-validate --tier %s%s%s%s%s%s%s` (docs/validation.md "
             "explains the "
             "cases, criteria and settings%s).",
         when, mach, h->nranks, h->threads, wall_s, wall_s / 60, cost, cost / 60, ncached,
         h->nruns, npass, nfail, nother, t->name, h->overrides[0] ? " " : "", h->overrides,
         h->materials == DEM_SCENE_HERTZ_JKR ? " --materials " : "",
         h->materials == DEM_SCENE_HERTZ_JKR ? dem_scene_materials_names[h->materials] : "",
         h->cases_arg ? " --case " : "", h->cases_arg ? h->cases_arg : "",
         h->overrides[0] ? "; the tier's settings are overridden here" : "");
  d_para(&d, "Scene: %s with "
             "every stiffness scaled by %g (by %g on the beds of the high-rate cases 10 and "
             "11), die %g d, reference bed %g d, reference sphere "
             "%g d, pre-consolidation 10 kPa, all rates gamma* = %g (gamma_dot = v / h_bed) "
             "unless varied, except that a bed deeper than the reference is consolidated and "
             "indented at the reference bed's speed in m/s (gamma* x reference / bed; the "
             "bed table lists it), dt = %g sqrt(m_min / k_max). Plateau window h/r %.2f-%.2f; "
             "early window %.2f-%.2f; significance level %.2f; %d replicate bed(s) (seeds "
             "1-%d: the runs of cases 1, 4 and 6 and of case 3's wall confinement on the "
             "shallow bed are made on each and judged over them, cases 2, 8 and 9 take the "
             "bed-to-bed spread from them).",
         h->materials == DEM_SCENE_HERTZ_JKR
             ? "chapter 5 materials (hertz-jkr: cohesive glass beads, Hertz + modified JKR "
               "between particles, thesis Tables 5.1-5.3; the indenter is Material 1 with "
               "friction 0.15), the materials of the thesis' runs behind cases 1-4"
             : "chapter 6/7 materials (pasha-simplified, thesis Tables 6.1-6.3)",
         t->stiffness_scale, t->rate_stiffness_scale, t->die, t->bed, t->indenter,
         t->gamma_star, t->dt_factor,
         t->plateau_lo, t->plateau_hi, t->early_lo, t->early_hi, h->level, t->replicates,
         t->replicates);

  d_head(&d, 2, "Summary");
  d_table_begin(&d);
  const char *hdr[] = {"case", "status", "criterion", "statistic", "ours", "thesis"};
  d_row(&d, 1, 6, hdr);
  for (int i = 0; i < nres; i++)
    for (int k = 0; k < res[i].nchecks; k++) {
      const vh_check *c = &res[i].checks[k];
      const char *cells[] = {k ? "" : res[i].name, vh_status_name(c->status), c->what,
                             c->statistic, c->ours[0] ? c->ours : "-", c->thesis};
      d_row(&d, 0, 6, cells);
    }
  d_table_end(&d);

  d_head(&d, 2, "Beds (each prepared once, reused by every indentation on it)");
  d_table_begin(&d);
  const char *bh[] = {"bed [d]", "die [d]", "seed", "mu", "Gamma [J/m^2]", "particles",
                      "solids fraction", "dt [s]", "preparation [s]", "stiffness scale",
                      "consolidation gamma*"};
  d_row(&d, 1, 11, bh);
  for (int i = 0; i < h->nbeds; i++) {
    const vh_bed *b = &h->beds[i];
    char c[11][48];
    snprintf(c[0], 48, "%g", b->bed), snprintf(c[1], 48, "%g", b->die);
    snprintf(c[2], 48, "%lu", b->seed), snprintf(c[3], 48, "%g", b->mu);
    snprintf(c[4], 48, "%g", b->gamma), snprintf(c[5], 48, "%zu", b->n);
    snprintf(c[6], 48, "%.3f", b->phi), snprintf(c[7], 48, "%.3g", b->dt);
    if (b->skipped) {
      for (int k = 5; k <= 7; k++) snprintf(c[k], 48, "-");
      snprintf(c[8], 48, "not made (over the --budget)");
    } else if (isfinite(b->prep_s) && b->wall_s < 0.5 * b->prep_s)
      snprintf(c[8], 48, "%.0f (earlier)", b->prep_s);
    else snprintf(c[8], 48, "%.0f", b->wall_s);
    snprintf(c[9], 48, "%g", b->kscale);
    snprintf(c[10], 48, "%.3g", b->gamma_star);
    const char *cells[11];
    for (int k = 0; k < 11; k++) cells[k] = c[k];
    d_row(&d, 0, 11, cells);
  }
  d_table_end(&d);

  for (int i = 0; i < nres; i++) {
    const vh_case_result *r = &res[i];
    d_head(&d, 2, "%d. %s: %s", i + 1, r->title, vh_status_name(r->status));
    d_para(&d, "Case `%s`, %s. Wall time of its new beds and runs in this invocation: %.0f "
               "s; the same beds and runs took %.0f s when they were made (cached ones "
               "included).%s%s", r->name, r->source, r->wall_s, r->cost_s,
           r->note[0] ? " " : "", r->note);
    if (r->has_rate_fit) {
      const dem_rate_fit *q = &r->rate_fit;
      char pv[48] = "";
      if (q->dof > 0) snprintf(pv, sizeof pv, ", p %.2g", q->p);
      char beds[48] = "";
      if (r->rate_fit_beds > 1)
        snprintf(beds, sizeof beds, " on %d replicate beds", r->rate_fit_beds);
      d_para(&d, "Reading of the rise (not a criterion): the weighted fit H = H0 + beta rho_b "
                 "v^2 over the %d runs made%s (v the indenter speed, rho_b = %.0f kg/m^3 the "
                 "particle density times the bed's solids fraction%s; docs/analysis.md, \"Rate "
                 "dependence\") gives H0 = %.2f +- %.2f kPa and beta = %.2f +- %.2f (chi2 %.2g "
                 "on %d dof%s%s). The dynamic part reaches %.0f %% of H0 at v = %.3g +- %.2g m/s, "
                 "gamma* %.2g +- %.2g (the thesis: H flat up to gamma* ~ 1).",
             q->dof + 2, beds, r->rho_b,
             r->rate_fit_beds > 1 ? ", the beds' mean, as is gamma* per m/s" : "", q->H0 / 1e3,
             q->H0_se / 1e3, q->beta, q->beta_se, q->chi2, q->dof, pv,
             q->scale > 1.0 ? "; errors scaled by sqrt(chi2/dof)" : "",
             100.0 * VH_RATE_ONSET_FRACTION, r->onset_v, r->onset_v_se, r->onset_gamma_star,
             r->onset_gamma_star_se);
    }
    for (int k = 0; k < 5; k++)
      if (r->plots[k][0]) d_img(&d, r->plots[k], r->plots[k]);
    d_table_begin(&d);
    const char *rh[] = {"run", "v [m/s]", "H [kPa]", "sd(H) [kPa]", "bin p [kPa]",
                        "bin q [kPa]", "bin phi", "Hc [kPa]", "a_c^2 / a(h)^2",
                        "surface sd [d]", "peak overlap [r]", "steps", "wall [s]", "status"};
    d_row(&d, 1, 14, rh);
    for (int k = 0; k < r->nruns; k++) {
      const vh_run *u = &h->runs[r->runs[k]];
      char c[14][96];
      snprintf(c[0], 96, "%s", r->labels[k]);
      if (isfinite(u->v)) snprintf(c[1], 96, "%.3g", u->v);
      else snprintf(c[1], 96, "-");
      const dem_series_stats sH = run_stats_of(u, &u->sH), sp = run_stats_of(u, &u->sp),
                             sq = run_stats_of(u, &u->sq), sphi = run_stats_of(u, &u->sphi);
      fmt_stats(c[2], 96, &sH, 1e-3);
      if (isfinite(sH.sd)) snprintf(c[3], 96, "%.3g", sH.sd / 1e3);
      else snprintf(c[3], 96, "-");
      fmt_stats(c[4], 96, &sp, 1e-3);
      fmt_stats(c[5], 96, &sq, 1e-3);
      fmt_stats(c[6], 96, &sphi, 1.0);
      const dem_series_stats sHc = run_stats_of(u, &u->sHc), sft = run_stats_of(u, &u->sfoot);
      fmt_stats(c[7], 96, &sHc, 1e-3);
      if (isfinite(sft.mean)) snprintf(c[8], 96, "%.3f", sft.mean);
      else snprintf(c[8], 96, "-");
      snprintf(c[9], 96, "%.2f", u->surface_sd / 1e-3);
      if (u->skipped) snprintf(c[10], 96, "-");
      else snprintf(c[10], 96, "%.3f", u->peak_overlap);
      snprintf(c[11], 96, "%ld", u->steps);
      snprintf(c[12], 96, "%.0f%s", u->wall_s, u->cached ? " (cached)" : "");
      snprintf(c[13], 96, "%.95s", u->status ? u->error : "ok");
      const char *cells[14];
      for (int j = 0; j < 14; j++) cells[j] = c[j];
      d_row(&d, 0, 14, cells);
    }
    d_table_end(&d);
  }
  d_head(&d, 2, "Speed versus accuracy, stability");
  d_para(&d, "The settings of the tiers (stiffness scale, gamma*, time-step factor, die size) "
             "are justified by the speed-versus-accuracy study and the stability map in "
             "docs/validation-study.md (`dem-bench-scene --study speed|stability`).");
  {
    /* the committed charts of that study (docs/study/), copied into the report folder: they
     * are not recomputed by this invocation, which the caption says */
    static const char *fig[][2] = {
        {"study_speed.png", "plateau H and its standard error against CPU time: stiffness "
                            "scale, gamma*, time-step factor, die (docs/study/, 2026-12-02, "
                            "beds at rest)"},
        {"study_stability.png", "stability map: where stiffness scale, time-step factor and "
                                "rate break the answer (docs/study/, 2026-12-05, current "
                                "beds, peak overlap of every step)"}};
    for (int i = 0; i < 2; i++) {
      char src[700];
      snprintf(src, sizeof src, "%s/docs/study/%s", VH_SOURCE_DIR, fig[i][0]);
      if (copy_file(src, h->out, fig[i][0]) == 0) {
        d_img(&d, fig[i][0], fig[i][1]);
        d_para(&d, "Figure: %s.", fig[i][1]);
      }
      else d_para(&d, "(%s: not found, the chart is in the source tree's docs/study/)", src);
    }
  }
  fputs("</body></html>\n", d.html);
  if ((rc = close_rename(d.md, tmd, h->out, "report.md", err))) {
    fclose(d.html);
    remove(thtml);
    return rc;
  }
  if ((rc = close_rename(d.html, thtml, h->out, "report.html", err))) return rc;

  char tj[800];
  FILE *f = open_tmp(h->out, "summary.json", tj, sizeof tj);
  if (!f) return dem_err_set(err, DEM_EIO, "dem-validate: cannot write summary.json");
  vh_json_print(h, res, nres, wall_s, f);
  return close_rename(f, tj, h->out, "summary.json", err);
}

static json_t *jnum(double v) { return isfinite(v) ? json_real(v) : json_null(); }

static json_t *jstats(const dem_series_stats *s) {
  return json_pack("{s:o,s:o,s:o,s:o,s:o}", "mean", jnum(s->mean), "se", jnum(s->se), "sd",
                   jnum(s->sd), "slope", jnum(s->slope), "n_eff", jnum(s->n_eff));
}

int vh_json_print(const vh *h, const vh_case_result *res, int nres, double wall_s, FILE *f) {
  json_t *root = json_object(), *cases = json_array(), *beds = json_array();
  const vh_tier *t = h->tier;
  json_object_set_new(root, "tier", json_string(t->name));
  json_object_set_new(root, "wall_s", jnum(wall_s));
  json_object_set_new(root, "threads", json_integer(h->threads));
  json_object_set_new(root, "ranks", json_integer(h->nranks));
  json_object_set_new(root, "budget_s", h->budget > 0 ? json_real(h->budget) : json_null());
  double cost = 0;
  for (int i = 0; i < nres; i++) cost += res[i].cost_s;
  json_object_set_new(root, "cost_s", jnum(cost));
  json_object_set_new(root, "level", jnum(h->level));
  json_object_set_new(root, "overrides",
                      h->overrides[0] ? json_string(h->overrides) : json_null());
  json_object_set_new(root, "settings",
                      json_pack("{s:s,s:f,s:f,s:f,s:f,s:f,s:f,s:f,s:f,s:[f,f],s:i}", "materials",
                                dem_scene_materials_names[h->materials],
                                "die_d", t->die, "shallow_die_d",
                                t->shallow_die > 0 ? t->shallow_die : t->die, "bed_d", t->bed,
                                "indenter_d", t->indenter, "gamma_star", t->gamma_star,
                                "stiffness_scale", t->stiffness_scale, "rate_stiffness_scale",
                                t->rate_stiffness_scale, "dt_factor", t->dt_factor,
                                "plateau_h_over_r", t->plateau_lo, t->plateau_hi,
                                "replicates", t->replicates));
  for (int i = 0; i < h->nbeds; i++) {
    const vh_bed *b = &h->beds[i];
    json_array_append_new(
        beds, json_pack("{s:f,s:f,s:I,s:f,s:f,s:f,s:I,s:o,s:o,s:o}", "bed_d", b->bed, "die_d",
                        b->die, "seed", (json_int_t)b->seed, "mu", b->mu, "gamma", b->gamma,
                        "stiffness_scale", b->kscale, "particles", (json_int_t)b->n,
                        "solids_fraction", jnum(b->phi), "dt", jnum(b->dt), "wall_s",
                        jnum(b->wall_s)));
    json_object_set_new(json_array_get(beds, json_array_size(beds) - 1), "prep_s",
                        jnum(b->prep_s));
    json_object_set_new(json_array_get(beds, json_array_size(beds) - 1), "skipped",
                        json_boolean(b->skipped));
    json_object_set_new(json_array_get(beds, json_array_size(beds) - 1), "gamma_star",
                        jnum(b->gamma_star));
  }
  for (int i = 0; i < nres; i++) {
    const vh_case_result *r = &res[i];
    json_t *c = json_object(), *checks = json_array(), *runs = json_array();
    json_object_set_new(c, "name", json_string(r->name));
    json_object_set_new(c, "title", json_string(r->title));
    json_object_set_new(c, "status", json_string(vh_status_name(r->status)));
    const vh_check *p = r->nchecks ? &r->checks[0] : NULL;
    json_object_set_new(c, "statistic", json_string(p ? p->statistic : ""));
    json_object_set_new(c, "ours", json_string(p ? p->ours : ""));
    json_object_set_new(c, "thesis", json_string(p ? p->thesis : ""));
    json_object_set_new(c, "wall_s", jnum(r->wall_s));
    json_object_set_new(c, "cost_s", jnum(r->cost_s));
    for (int k = 0; k < r->nchecks; k++) {
      const vh_check *q = &r->checks[k];
      json_array_append_new(checks, json_pack("{s:s,s:s,s:s,s:s,s:s}", "criterion", q->what,
                                              "status", vh_status_name(q->status), "statistic",
                                              q->statistic, "ours", q->ours, "thesis",
                                              q->thesis));
    }
    for (int k = 0; k < r->nruns; k++) {
      const vh_run *u = &h->runs[r->runs[k]];
      const dem_series_stats sH = run_stats_of(u, &u->sH), sp = run_stats_of(u, &u->sp),
                             sq = run_stats_of(u, &u->sq), sphi = run_stats_of(u, &u->sphi);
      json_t *j = json_pack("{s:s,s:s,s:o,s:o,s:o,s:o,s:o,s:o,s:I,s:o,s:I}", "label",
                            r->labels[k], "status", u->status ? u->error : "ok", "x",
                            jnum(r->x[k]), "H", jstats(&sH), "bin_p", jstats(&sp),
                            "bin_q", jstats(&sq), "bin_phi", jstats(&sphi), "wall_s",
                            jnum(u->wall_s), "steps", (json_int_t)u->steps, "dt", jnum(u->dt),
                            "samples", (json_int_t)u->n);
      json_object_set_new(j, "cached", json_boolean(u->cached));
      json_object_set_new(j, "skipped", json_boolean(u->skipped));
      json_object_set_new(j, "threads", json_integer(u->threads));
      json_object_set_new(j, "peak_overlap_frac", u->skipped ? json_null() : jnum(u->peak_overlap));
      json_object_set_new(j, "speed_m_s", jnum(u->v));
      /* the footprint of the indenter's contacts (docs/analysis.md 2b) */
      const dem_series_stats sHc = run_stats_of(u, &u->sHc), sft = run_stats_of(u, &u->sfoot);
      json_object_set_new(j, "Hc", jstats(&sHc));
      json_object_set_new(j, "footprint_ratio", jstats(&sft));
      json_array_append_new(runs, j);
    }
    json_object_set_new(c, "checks", checks);
    json_object_set_new(c, "runs", runs);
    if (r->has_rate_fit) {
      const dem_rate_fit *q = &r->rate_fit;
      json_t *fit = json_pack(
          "{s:i,s:o,s:o,s:o,s:o,s:o,s:o,s:o,s:i,s:o,s:o,s:f,s:o,s:o,s:o,s:o}", "beds",
          r->rate_fit_beds, "rho_b", jnum(r->rho_b), "H0", jnum(q->H0), "H0_se", jnum(q->H0_se),
          "beta", jnum(q->beta), "beta_se", jnum(q->beta_se), "cov", jnum(q->cov), "chi2",
          jnum(q->chi2), "dof", q->dof, "p", jnum(q->p), "scale", jnum(q->scale),
          "onset_fraction", VH_RATE_ONSET_FRACTION, "onset_speed_m_s", jnum(r->onset_v),
          "onset_speed_se", jnum(r->onset_v_se), "onset_gamma_star", jnum(r->onset_gamma_star),
          "onset_gamma_star_se", jnum(r->onset_gamma_star_se));
      json_object_set_new(c, "rate_fit", fit);
    } else {
      json_object_set_new(c, "rate_fit", json_null());
    }
    json_array_append_new(cases, c);
  }
  json_object_set_new(root, "beds", beds);
  json_object_set_new(root, "cases", cases);
  int rc = json_dumpf(root, f, JSON_INDENT(1) | JSON_REAL_PRECISION(8));
  fputc('\n', f);
  json_decref(root);
  return rc;
}
