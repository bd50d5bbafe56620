/* HDF5 checkpoints of the engine (dem/checkpoint.h).
 *
 * Layout (version 3; version 2 had no dashpot part of the wall loads, version 1 no wall
 * length and angle and no clock base), all
 * datasets in the root group; counts that may be zero are stored with at least one element
 * (the true counts are in "meta_i"):
 *   format        uint8[16]   "dem-checkpoint" (zero padded)
 *   version       int32[1]    DEM_CHECKPOINT_VERSION
 *   meta_i        int64[NI]   integer state (enum MI below)
 *   meta_d        double[ND]  real state (enum MD below)
 *   rho           double[nmat]            kg/m^3
 *   inter_ab      int32[ni, 2]            material pair (a <= b) of each interaction
 *   inter_law     uint8[ni, 64]           law name
 *   inter_sig     uint64[ni]              signature of the law's table (name, ncoef, nhist,
 *                                         flags, coefficient keys and units)
 *   inter_c       double[ni, NCOEF_MAX]   the compiled coefficient array
 *   inter_tr      double[ni, 6]           tangential kind, kt, G, mu, eta; rolling mu_r
 *   x v omega f torque x0   double[n, 3]  (x0: positions at the last neighbour-list build)
 *   radius mass inertia     double[n]
 *   material int32[n], id uint32[n]
 *   wall_d        double[nwall, WD]       spec, loads, work, build point, servo (enum WD)
 *   wall_nlist    int64[nwall]; wall_list uint32[sum]; wall_hist double[nwall, n, nh]
 *   nl_first      uint32[n + 1]; nl_nbr uint32[npairs]; nl_hist double[npairs, nh];
 *   nl_touch      uint8[npairs]     the half neighbour list: pair keys (row i, nbr j) and
 *                                   their history blocks
 *   user          uint8[len]        the caller's blob
 *   checksum      uint64[1]         FNV-1a over the bytes of every dataset above, in order
 * HDF5's own error printing is silenced for the duration of a call (H5Eset_auto2).
 */
#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dem/checkpoint.h"
#include "internal.h"

#define FORMAT_TAG "dem-checkpoint"
#define LAWNAME_LEN 64

enum {
  MI_N, MI_NMAT, MI_NWALL, MI_NINTER, MI_NH, MI_HOFF, MI_NTHREADS, MI_SORT_EVERY,
  MI_BUILDS_SINCE_SORT, MI_NEED_BUILD, MI_NEED_FORCES, MI_STEPS, MI_REBUILDS, MI_SORTS,
  MI_NPAIRS, MI_LAST_GOOD, MI_USER_LEN, MI_CHECK_INTERVAL, MI_KE_STRIKES, MI_HAVE_LIST,
  MI_CONTACTS, MI_WALL_CONTACTS, MI_STEPS_BASE, NI
};
enum {
  MD_DT, MD_G0, MD_G1, MD_G2, MD_SKIN, MD_TIME, MD_MAX_OVERLAP_FRAC, MD_KE_GROWTH, MD_KE_FLOOR,
  MD_STAT_MAX_OVERLAP, MD_KE, MD_T_BASE, ND
};
enum {
  WD_KIND, WD_P = 1, WD_N = 4, WD_RADIUS = 7, WD_V = 8, WD_MATERIAL = 11, WD_F = 12, WD_T = 15,
  WD_WORK = 18, WD_PBUILD = 19, WD_SERVO = 22, WD_FTARGET, WD_GAIN, WD_VMAX, WD_LENGTH,
  WD_ANGLE, WD_FD, WD = WD_FD + 3
};

/* ---- checksum ---- */
typedef struct { uint64_t h; } fnv;
static void fnv_init(fnv *c) { c->h = 1469598103934665603ull; }
static void fnv_add(fnv *c, const void *data, size_t len) {
  const unsigned char *b = data;
  uint64_t h = c->h;
  for (size_t k = 0; k < len; k++) {
    h ^= b[k];
    h *= 1099511628211ull;
  }
  c->h = h;
}

/* A signature of a law's table: changes when the law's name, sizes, flags or coefficient
 * keys/units change (then a compiled array from an older build cannot be trusted). */
static uint64_t law_signature(const dem_law *law) {
  fnv c;
  fnv_init(&c);
  fnv_add(&c, law->name, strlen(law->name) + 1);
  int32_t k[3] = {law->ncoef, law->nhist, (int32_t)law->flags};
  fnv_add(&c, k, sizeof k);
  for (int q = 0; q < law->ncoef; q++) {
    fnv_add(&c, law->coef[q].key, strlen(law->coef[q].key) + 1);
    if (law->coef[q].unit) fnv_add(&c, law->coef[q].unit, strlen(law->coef[q].unit) + 1);
  }
  return c.h;
}

/* ---- writing ---- */
typedef struct wctx {
  hid_t file;
  fnv sum;
  const char *path;
  dem_err *err;
  int rc;
} wctx;

static size_t type_size(hid_t t) { return H5Tget_size(t); }

/* Write dataset name of rank 1 or 2 (d1 = 0 for rank 1); d0 = 0 is stored as 1 element
 * taken from a zero pad. */
static void put(wctx *w, const char *name, hid_t type, size_t d0, size_t d1, const void *data) {
  if (w->rc) return;
  static const unsigned char zero[64 * 8] = {0};
  size_t row = d1 ? d1 : 1;
  const void *src = data;
  hsize_t dims[2] = {d0 ? d0 : 1, row};
  size_t bytes = (size_t)dims[0] * row * type_size(type);
  void *pad = NULL;
  if (d0 == 0) {
    if (bytes <= sizeof zero) src = zero;
    else src = pad = calloc(1, bytes);
    if (!src) {
      w->rc = dem_err_set(w->err, DEM_ENOMEM, "%s: out of memory", w->path);
      return;
    }
  }
  hid_t sp = H5Screate_simple(d1 ? 2 : 1, dims, NULL);
  hid_t ds = sp >= 0 ? H5Dcreate2(w->file, name, type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
  if (ds < 0 || H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, src) < 0)
    w->rc = dem_err_set(w->err, DEM_EIO, "%s: cannot write dataset '%s'", w->path, name);
  else fnv_add(&w->sum, src, bytes);
  if (ds >= 0) H5Dclose(ds);
  if (sp >= 0) H5Sclose(sp);
  free(pad);
}

static int sync_file(const char *path) {
  int fd = open(path, O_RDONLY);
  if (fd < 0) return -1;
  int r = fsync(fd);
  close(fd);
  return r;
}

int dem_sim_checkpoint_write(const dem_sim *s, const char *path, const void *user,
                             size_t user_len, dem_err *err) {
  const dem_particles *p = &s->p;
  const size_t n = p->n;
  const int nh = s->nh;
  const int have_list = nh > 0 && s->nl.first && s->nl.n == n;
  const size_t npairs = have_list ? s->nl.npairs : 0;
  char tmp[4096];
  snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());

  /* interactions a <= b that are set */
  int ni = 0;
  int32_t ab[DEM_ENGINE_MAX_MATERIALS * DEM_ENGINE_MAX_MATERIALS][2];
  for (int a = 0; a < s->nmat; a++)
    for (int b = a; b < s->nmat; b++)
      if (s->inter[a][b].set) {
        ab[ni][0] = a;
        ab[ni][1] = b;
        ni++;
      }
  unsigned char lawname[DEM_ENGINE_MAX_MATERIALS * DEM_ENGINE_MAX_MATERIALS][LAWNAME_LEN];
  uint64_t sig[DEM_ENGINE_MAX_MATERIALS * DEM_ENGINE_MAX_MATERIALS];
  double coef[DEM_ENGINE_MAX_MATERIALS * DEM_ENGINE_MAX_MATERIALS][DEM_LAW_NCOEF_MAX];
  double tr[DEM_ENGINE_MAX_MATERIALS * DEM_ENGINE_MAX_MATERIALS][6];
  memset(lawname, 0, sizeof lawname);
  for (int k = 0; k < ni; k++) {
    const dem_inter *in = &s->inter[ab[k][0]][ab[k][1]];
    snprintf((char *)lawname[k], LAWNAME_LEN, "%s", in->normal.law->name);
    sig[k] = law_signature(in->normal.law);
    memcpy(coef[k], in->normal.c, sizeof coef[k]);
    tr[k][0] = (double)in->tang.kind;
    tr[k][1] = in->tang.kt;
    tr[k][2] = in->tang.G;
    tr[k][3] = in->tang.mu;
    tr[k][4] = in->tang.eta;
    tr[k][5] = in->roll.mu_r;
  }

  int64_t mi[NI] = {0};
  mi[MI_N] = (int64_t)n;
  mi[MI_NMAT] = s->nmat;
  mi[MI_NWALL] = s->nwall;
  mi[MI_NINTER] = ni;
  mi[MI_NH] = nh;
  mi[MI_HOFF] = s->hoff;
  mi[MI_NTHREADS] = s->nthreads;
  mi[MI_SORT_EVERY] = s->sort_every;
  mi[MI_BUILDS_SINCE_SORT] = s->builds_since_sort;
  mi[MI_NEED_BUILD] = s->need_build || !have_list;
  mi[MI_NEED_FORCES] = s->need_forces;
  mi[MI_STEPS] = s->st.steps;
  mi[MI_REBUILDS] = s->st.rebuilds;
  mi[MI_SORTS] = s->st.sorts;
  mi[MI_NPAIRS] = (int64_t)npairs;
  mi[MI_LAST_GOOD] = s->last_good;
  mi[MI_USER_LEN] = user ? (int64_t)user_len : 0;
  mi[MI_CHECK_INTERVAL] = s->bd.check_interval;
  mi[MI_KE_STRIKES] = s->bd.ke_strikes;
  mi[MI_HAVE_LIST] = have_list;
  mi[MI_CONTACTS] = (int64_t)s->st.contacts;
  mi[MI_WALL_CONTACTS] = (int64_t)s->st.wall_contacts;
  mi[MI_STEPS_BASE] = s->steps_base;
  double md[ND] = {0};
  md[MD_DT] = s->dt;
  md[MD_G0] = s->g[0];
  md[MD_G1] = s->g[1];
  md[MD_G2] = s->g[2];
  md[MD_SKIN] = s->skin;
  md[MD_TIME] = s->st.time;
  md[MD_MAX_OVERLAP_FRAC] = s->bd.max_overlap_frac;
  md[MD_KE_GROWTH] = s->bd.ke_growth;
  md[MD_KE_FLOOR] = s->bd.ke_floor;
  md[MD_STAT_MAX_OVERLAP] = s->st.max_overlap_frac;
  md[MD_KE] = s->st.kinetic_energy;
  md[MD_T_BASE] = s->t_base;

  H5E_auto2_t old_fn;
  void *old_data;
  H5Eget_auto2(H5E_DEFAULT, &old_fn, &old_data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  wctx w = {.path = tmp, .err = err, .rc = DEM_OK};
  fnv_init(&w.sum);
  w.file = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (w.file < 0) w.rc = dem_err_set(err, DEM_EIO, "%s: cannot create the HDF5 file", tmp);
  unsigned char tag[16] = {0};
  memcpy(tag, FORMAT_TAG, strlen(FORMAT_TAG));
  int32_t version = DEM_CHECKPOINT_VERSION;
  put(&w, "format", H5T_NATIVE_UCHAR, 16, 0, tag);
  put(&w, "version", H5T_NATIVE_INT32, 1, 0, &version);
  put(&w, "meta_i", H5T_NATIVE_INT64, NI, 0, mi);
  put(&w, "meta_d", H5T_NATIVE_DOUBLE, ND, 0, md);
  put(&w, "rho", H5T_NATIVE_DOUBLE, (size_t)s->nmat, 0, s->rho);
  put(&w, "inter_ab", H5T_NATIVE_INT32, (size_t)ni, 2, ab);
  put(&w, "inter_law", H5T_NATIVE_UCHAR, (size_t)ni, LAWNAME_LEN, lawname);
  put(&w, "inter_sig", H5T_NATIVE_UINT64, (size_t)ni, 0, sig);
  put(&w, "inter_c", H5T_NATIVE_DOUBLE, (size_t)ni, DEM_LAW_NCOEF_MAX, coef);
  put(&w, "inter_tr", H5T_NATIVE_DOUBLE, (size_t)ni, 6, tr);
  put(&w, "x", H5T_NATIVE_DOUBLE, n, 3, p->x);
  put(&w, "v", H5T_NATIVE_DOUBLE, n, 3, p->v);
  put(&w, "omega", H5T_NATIVE_DOUBLE, n, 3, p->omega);
  put(&w, "f", H5T_NATIVE_DOUBLE, n, 3, p->f);
  put(&w, "torque", H5T_NATIVE_DOUBLE, n, 3, p->torque);
  put(&w, "x0", H5T_NATIVE_DOUBLE, have_list ? n : 0, 3, s->x0);
  put(&w, "radius", H5T_NATIVE_DOUBLE, n, 0, p->radius);
  put(&w, "mass", H5T_NATIVE_DOUBLE, n, 0, p->mass);
  put(&w, "inertia", H5T_NATIVE_DOUBLE, n, 0, p->inertia);
  put(&w, "material", H5T_NATIVE_INT, n, 0, p->material);
  put(&w, "id", H5T_NATIVE_UINT32, n, 0, p->id);

  /* walls */
  double wd[DEM_ENGINE_MAX_WALLS][WD];
  int64_t wn[DEM_ENGINE_MAX_WALLS];
  size_t wtot = 0;
  for (int k = 0; k < s->nwall; k++) {
    const dem_wall *wl = &s->wall[k];
    double *d = wd[k];
    d[WD_KIND] = (double)wl->spec.kind;
    for (int c = 0; c < 3; c++) {
      d[WD_P + c] = wl->spec.p[c];
      d[WD_N + c] = wl->spec.n[c];
      d[WD_V + c] = wl->spec.v[c];
      d[WD_F + c] = wl->f[c];
      d[WD_FD + c] = wl->fd[c];
      d[WD_T + c] = wl->t[c];
      d[WD_PBUILD + c] = wl->p_build[c];
    }
    d[WD_RADIUS] = wl->spec.radius;
    d[WD_LENGTH] = wl->spec.length;
    d[WD_ANGLE] = wl->spec.angle;
    d[WD_MATERIAL] = (double)wl->spec.material;
    d[WD_WORK] = wl->work;
    d[WD_SERVO] = (double)wl->servo;
    d[WD_FTARGET] = wl->f_target;
    d[WD_GAIN] = wl->gain;
    d[WD_VMAX] = wl->v_max;
    wn[k] = have_list ? (int64_t)wl->nlist : 0;
    wtot += (size_t)wn[k];
  }
  put(&w, "wall_d", H5T_NATIVE_DOUBLE, (size_t)s->nwall, WD, wd);
  put(&w, "wall_nlist", H5T_NATIVE_INT64, (size_t)s->nwall, 0, wn);
  uint32_t *wlist = malloc((wtot ? wtot : 1) * sizeof *wlist);
  double *whist = nh > 0 ? malloc(((size_t)s->nwall * n > 0 ? (size_t)s->nwall * n : 1) * (size_t)nh * sizeof *whist) : NULL;
  if (!wlist || (nh > 0 && !whist)) {
    if (!w.rc) w.rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", tmp);
  } else {
    size_t at = 0;
    for (int k = 0; k < s->nwall; k++) {
      if (wn[k]) memcpy(wlist + at, s->wall[k].list, (size_t)wn[k] * sizeof *wlist);
      at += (size_t)wn[k];
      if (nh > 0 && n > 0) {
        if (s->wall[k].hist)
          memcpy(whist + (size_t)k * n * nh, s->wall[k].hist, n * (size_t)nh * sizeof *whist);
        else memset(whist + (size_t)k * n * nh, 0, n * (size_t)nh * sizeof *whist);
      }
    }
    put(&w, "wall_list", H5T_NATIVE_UINT32, wtot, 0, wlist);
    put(&w, "wall_hist", H5T_NATIVE_DOUBLE, nh > 0 ? (size_t)s->nwall * n : 0,
        nh > 0 ? (size_t)nh : 1, whist);
  }
  free(wlist);
  free(whist);

  /* neighbour list */
  put(&w, "nl_first", H5T_NATIVE_UINT32, have_list ? n + 1 : 0, 0, s->nl.first);
  put(&w, "nl_nbr", H5T_NATIVE_UINT32, npairs, 0, s->nl.nbr);
  put(&w, "nl_hist", H5T_NATIVE_DOUBLE, npairs, nh > 0 ? (size_t)nh : 1, s->nl.hist);
  put(&w, "nl_touch", H5T_NATIVE_UINT8, npairs, 0, s->nl.touch);
  put(&w, "user", H5T_NATIVE_UCHAR, user ? user_len : 0, 0, user);
  uint64_t sum = w.sum.h;
  put(&w, "checksum", H5T_NATIVE_UINT64, 1, 0, &sum);

  if (w.file >= 0 && H5Fclose(w.file) < 0 && w.rc == DEM_OK)
    w.rc = dem_err_set(err, DEM_EIO, "%s: cannot close the HDF5 file", tmp);
  H5Eset_auto2(H5E_DEFAULT, old_fn, old_data);
  if (w.rc == DEM_OK && sync_file(tmp) != 0)
    w.rc = dem_err_set(err, DEM_EIO, "%s: cannot flush to disk: %s", tmp, strerror(errno));
  if (w.rc == DEM_OK && rename(tmp, path) != 0)
    w.rc = dem_err_set(err, DEM_EIO, "%s: cannot rename the finished temporary file %s: %s",
                       path, tmp, strerror(errno));
  if (w.rc) remove(tmp);
  return w.rc;
}

/* ---- reading ---- */
typedef struct rctx {
  hid_t file;
  fnv sum;
  const char *path;
  dem_err *err;
  int rc;
} rctx;

/* Read dataset name, which must have shape [d0 (at least 1), d1] (d1 = 0: rank 1). */
static void get(rctx *r, const char *name, hid_t type, size_t d0, size_t d1, void *data) {
  if (r->rc) return;
  size_t row = d1 ? d1 : 1;
  hsize_t want[2] = {d0 ? d0 : 1, row};
  int rank = d1 ? 2 : 1;
  size_t bytes = (size_t)want[0] * row * type_size(type);
  void *pad = NULL, *dst = data;
  if (d0 == 0) dst = pad = malloc(bytes);
  if (!dst) {
    r->rc = dem_err_set(r->err, DEM_ENOMEM, "%s: out of memory", r->path);
    return;
  }
  hid_t ds = H5Dopen2(r->file, name, H5P_DEFAULT);
  if (ds < 0) {
    r->rc = dem_err_set(r->err, DEM_EPARSE, "%s: not a usable checkpoint: dataset '%s' is missing",
                        r->path, name);
    free(pad);
    return;
  }
  hid_t sp = H5Dget_space(ds);
  hsize_t dims[2] = {0, 0};
  int rk = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
  if (rk == rank) H5Sget_simple_extent_dims(sp, dims, NULL);
  if (rk != rank || dims[0] != want[0] || (rank == 2 && dims[1] != want[1])) {
    r->rc = dem_err_set(r->err, DEM_EPARSE,
                        "%s: dataset '%s' has rank %d and shape [%llu, %llu]; expected rank %d, "
                        "[%llu, %llu]",
                        r->path, name, rk, (unsigned long long)dims[0],
                        (unsigned long long)dims[1], rank, (unsigned long long)want[0],
                        (unsigned long long)(rank == 2 ? want[1] : 0));
  } else if (H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, dst) < 0) {
    r->rc = dem_err_set(r->err, DEM_EIO, "%s: cannot read dataset '%s' (file damaged?)",
                        r->path, name);
  } else {
    fnv_add(&r->sum, dst, bytes);
  }
  if (sp >= 0) H5Sclose(sp);
  H5Dclose(ds);
  free(pad);
}

static int bad(rctx *r, const char *what, long long value, const char *allowed) {
  if (r->rc) return r->rc;
  return r->rc = dem_err_set(r->err, DEM_EPARSE, "%s: %s = %lld (allowed %s)", r->path, what,
                             value, allowed);
}

/* The state of a simulation read back: everything dem_sim_create does not set. */
static int restore(rctx *r, dem_sim **out, void **user, size_t *user_len) {
  dem_err *err = r->err;
  const char *path = r->path;
  unsigned char tag[16];
  int32_t version = 0;
  get(r, "format", H5T_NATIVE_UCHAR, 16, 0, tag);
  if (!r->rc && memcmp(tag, FORMAT_TAG, strlen(FORMAT_TAG)) != 0)
    return r->rc = dem_err_set(err, DEM_EPARSE, "%s: not a dem checkpoint (format tag)", path);
  get(r, "version", H5T_NATIVE_INT32, 1, 0, &version);
  if (!r->rc && version != DEM_CHECKPOINT_VERSION)
    return r->rc = dem_err_set(err, DEM_EUNSUPPORTED,
                               "%s: checkpoint format version %d; this build reads version %d "
                               "only%s",
                               path, (int)version, DEM_CHECKPOINT_VERSION,
                               version < DEM_CHECKPOINT_VERSION
                                   ? " (written by an older build: version 3 added the "
                                     "dashpot part of the wall loads, version 2 the "
                                     "indenter length and angle and the clock base; rerun "
                                     "to write a new checkpoint)"
                                   : " (written by a newer build)");
  int64_t mi[NI];
  double md[ND];
  get(r, "meta_i", H5T_NATIVE_INT64, NI, 0, mi);
  get(r, "meta_d", H5T_NATIVE_DOUBLE, ND, 0, md);
  if (r->rc) return r->rc;
  const int64_t n = mi[MI_N];
  if (n < 0 || n > (int64_t)UINT32_MAX - 2) return bad(r, "particles", n, "[0, 2^32 - 2]");
  if (mi[MI_NMAT] < 0 || mi[MI_NMAT] > DEM_ENGINE_MAX_MATERIALS)
    return bad(r, "materials", mi[MI_NMAT], "[0, DEM_ENGINE_MAX_MATERIALS]");
  if (mi[MI_NWALL] < 0 || mi[MI_NWALL] > DEM_ENGINE_MAX_WALLS)
    return bad(r, "walls", mi[MI_NWALL], "[0, DEM_ENGINE_MAX_WALLS]");
  if (mi[MI_NINTER] < 0 || mi[MI_NINTER] > mi[MI_NMAT] * (mi[MI_NMAT] + 1) / 2)
    return bad(r, "interactions", mi[MI_NINTER], "[0, nmat (nmat + 1) / 2]");
  if (mi[MI_NH] != 0 && (mi[MI_HOFF] < 1 || mi[MI_HOFF] > DEM_LAW_NHIST_MAX ||
                         mi[MI_NH] != mi[MI_HOFF] + DEM_TANGENTIAL_NHIST))
    return bad(r, "history block size", mi[MI_NH], "0 or law block + tangential spring");
  if (mi[MI_NTHREADS] < 1 || mi[MI_NTHREADS] > DEM_MAX_THREADS)
    return bad(r, "threads", mi[MI_NTHREADS], "[1, DEM_MAX_THREADS]");
  if (mi[MI_NPAIRS] < 0 || mi[MI_NPAIRS] > (int64_t)UINT32_MAX)
    return bad(r, "pairs", mi[MI_NPAIRS], "[0, 2^32]");
  if (mi[MI_USER_LEN] < 0 || mi[MI_USER_LEN] > ((int64_t)1 << 40))
    return bad(r, "user blob length", mi[MI_USER_LEN], "[0, 2^40]");
  if (mi[MI_HAVE_LIST] && mi[MI_NH] == 0) return bad(r, "have_list", 1, "0 when nh = 0");
  if (mi[MI_STEPS_BASE] < 0 || mi[MI_STEPS_BASE] > mi[MI_STEPS])
    return bad(r, "clock base step", mi[MI_STEPS_BASE], "[0, steps]");
  const size_t nn = (size_t)n;
  const int nmat = (int)mi[MI_NMAT], nwall = (int)mi[MI_NWALL], ni = (int)mi[MI_NINTER];
  const int nh = (int)mi[MI_NH], have_list = mi[MI_HAVE_LIST] != 0;
  const size_t npairs = have_list ? (size_t)mi[MI_NPAIRS] : 0;

  dem_sim *s = dem_sim_create(err);
  if (!s) return r->rc = DEM_ENOMEM;
  *out = s;
  double rho[DEM_ENGINE_MAX_MATERIALS];
  get(r, "rho", H5T_NATIVE_DOUBLE, (size_t)nmat, 0, rho);
  if (r->rc) return r->rc;
  for (int k = 0; k < nmat; k++)
    if (dem_sim_add_material(s, rho[k], NULL, err))
      return r->rc = dem_err_set(err, DEM_EPARSE, "%s: material %d: %s", path, k, err->msg);

  enum { NIMAX = DEM_ENGINE_MAX_MATERIALS * DEM_ENGINE_MAX_MATERIALS };
  int32_t ab[NIMAX][2];
  unsigned char lawname[NIMAX][LAWNAME_LEN];
  uint64_t sig[NIMAX];
  double coef[NIMAX][DEM_LAW_NCOEF_MAX], tr[NIMAX][6];
  get(r, "inter_ab", H5T_NATIVE_INT32, (size_t)ni, 2, ab);
  get(r, "inter_law", H5T_NATIVE_UCHAR, (size_t)ni, LAWNAME_LEN, lawname);
  get(r, "inter_sig", H5T_NATIVE_UINT64, (size_t)ni, 0, sig);
  get(r, "inter_c", H5T_NATIVE_DOUBLE, (size_t)ni, DEM_LAW_NCOEF_MAX, coef);
  get(r, "inter_tr", H5T_NATIVE_DOUBLE, (size_t)ni, 6, tr);
  if (r->rc) return r->rc;
  for (int k = 0; k < ni; k++) {
    lawname[k][LAWNAME_LEN - 1] = 0;
    const char *name = (const char *)lawname[k];
    const dem_law *law = dem_contact_law_find(name);
    if (!law)
      return r->rc = dem_err_set(err, DEM_ENOTFOUND,
                                 "%s: interaction (%d, %d): unknown law '%s' (not in this "
                                 "build's law table)",
                                 path, (int)ab[k][0], (int)ab[k][1], name);
    if (law_signature(law) != sig[k])
      return r->rc = dem_err_set(err, DEM_EINVAL,
                                 "%s: interaction (%d, %d): law '%s' of this build differs from "
                                 "the one that wrote the checkpoint (coefficients, history size "
                                 "or flags changed)",
                                 path, (int)ab[k][0], (int)ab[k][1], name);
    if (tr[k][0] != 0.0 && tr[k][0] != 1.0 && tr[k][0] != 2.0)
      return bad(r, "tangential kind", (long long)tr[k][0], "0, 1, 2");
    dem_contact ct;
    memset(&ct, 0, sizeof ct);
    ct.law = law;
    memcpy(ct.c, coef[k], sizeof ct.c);
    dem_tangential t;
    memset(&t, 0, sizeof t);
    t.kind = (dem_tangential_kind)(int)tr[k][0];
    t.kt = tr[k][1];
    t.G = tr[k][2];
    t.mu = tr[k][3];
    t.eta = tr[k][4];
    dem_rolling ro = {.mu_r = tr[k][5]};
    if (dem_sim_set_interaction(s, ab[k][0], ab[k][1], &ct, &t, &ro, err))
      return r->rc = dem_err_set(err, DEM_EPARSE, "%s: %s", path, err->msg);
  }

  /* particles */
  if (dem_engine_grow(s, nn ? nn : 1, err)) return r->rc = err->code;
  dem_particles *p = &s->p;
  get(r, "x", H5T_NATIVE_DOUBLE, nn, 3, p->x);
  get(r, "v", H5T_NATIVE_DOUBLE, nn, 3, p->v);
  get(r, "omega", H5T_NATIVE_DOUBLE, nn, 3, p->omega);
  get(r, "f", H5T_NATIVE_DOUBLE, nn, 3, p->f);
  get(r, "torque", H5T_NATIVE_DOUBLE, nn, 3, p->torque);
  get(r, "x0", H5T_NATIVE_DOUBLE, have_list ? nn : 0, 3, s->x0);
  get(r, "radius", H5T_NATIVE_DOUBLE, nn, 0, p->radius);
  get(r, "mass", H5T_NATIVE_DOUBLE, nn, 0, p->mass);
  get(r, "inertia", H5T_NATIVE_DOUBLE, nn, 0, p->inertia);
  get(r, "material", H5T_NATIVE_INT, nn, 0, p->material);
  get(r, "id", H5T_NATIVE_UINT32, nn, 0, p->id);
  if (r->rc) return r->rc;
  for (size_t i = 0; i < nn; i++)
    if (p->material[i] < 0 || p->material[i] >= nmat)
      return bad(r, "particle material", p->material[i], "[0, nmat)");
  p->n = nn;

  /* walls */
  double wd[DEM_ENGINE_MAX_WALLS][WD];
  int64_t wn[DEM_ENGINE_MAX_WALLS];
  get(r, "wall_d", H5T_NATIVE_DOUBLE, (size_t)nwall, WD, wd);
  get(r, "wall_nlist", H5T_NATIVE_INT64, (size_t)nwall, 0, wn);
  if (r->rc) return r->rc;
  size_t wtot = 0;
  for (int k = 0; k < nwall; k++) {
    if (wn[k] < 0 || wn[k] > n) return bad(r, "wall list length", wn[k], "[0, particles]");
    wtot += (size_t)wn[k];
    const double *d = wd[k];
    dem_wall_spec ws;
    memset(&ws, 0, sizeof ws);
    /* Every kind of dem_wall_kind, indenters included (their state is the same spec). */
    if (!(d[WD_KIND] >= DEM_WALL_PLANE && d[WD_KIND] <= DEM_WALL_BOX) ||
        d[WD_KIND] != (double)(int)d[WD_KIND])
      return bad(r, "wall kind", (long long)d[WD_KIND], "0 to 5 (dem_wall_kind)");
    ws.kind = (dem_wall_kind)(int)d[WD_KIND];
    for (int c = 0; c < 3; c++) {
      ws.p[c] = d[WD_P + c];
      ws.n[c] = d[WD_N + c];
      ws.v[c] = d[WD_V + c];
    }
    ws.radius = d[WD_RADIUS];
    ws.length = d[WD_LENGTH];
    ws.angle = d[WD_ANGLE];
    ws.material = (int)d[WD_MATERIAL];
    if (dem_sim_add_wall(s, &ws, NULL, err))
      return r->rc = dem_err_set(err, DEM_EPARSE, "%s: %s", path, err->msg);
    dem_wall *wl = &s->wall[k];
    for (int c = 0; c < 3; c++) {
      wl->spec.n[c] = d[WD_N + c]; /* bit-exact, not re-normalised */
      wl->f[c] = d[WD_F + c];
      wl->fd[c] = d[WD_FD + c];
      wl->t[c] = d[WD_T + c];
      wl->p_build[c] = d[WD_PBUILD + c];
    }
    wl->work = d[WD_WORK];
    wl->servo = d[WD_SERVO] != 0.0;
    wl->f_target = d[WD_FTARGET];
    wl->gain = d[WD_GAIN];
    wl->v_max = d[WD_VMAX];
  }
  uint32_t *wlist = malloc((wtot ? wtot : 1) * sizeof *wlist);
  if (!wlist) return r->rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
  get(r, "wall_list", H5T_NATIVE_UINT32, wtot, 0, wlist);
  size_t at = 0;
  for (int k = 0; k < nwall && !r->rc; k++) {
    dem_wall *wl = &s->wall[k];
    size_t m = (size_t)wn[k];
    wl->list = malloc((m ? m : 1) * sizeof *wl->list);
    if (!wl->list) {
      r->rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
      break;
    }
    wl->cap_list = m ? m : 1;
    for (size_t q = 0; q < m; q++)
      if (wlist[at + q] >= nn || (q > 0 && wlist[at + q] <= wlist[at + q - 1])) {
        bad(r, "wall list entry", wlist[at + q], "ascending particle indices");
        break;
      }
    memcpy(wl->list, wlist + at, m * sizeof *wl->list);
    wl->nlist = m;
    at += m;
  }
  free(wlist);
  if (r->rc) return r->rc;
  if (nh > 0) {
    s->nh = nh;
    s->hoff = (int)mi[MI_HOFF];
    for (int k = 0; k < nwall; k++) {
      s->wall[k].hist = calloc(s->cap, (size_t)nh * sizeof(double));
      if (!s->wall[k].hist) return r->rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
    }
    double *whist = malloc(((size_t)nwall * nn > 0 ? (size_t)nwall * nn : 1) * (size_t)nh * sizeof *whist);
    if (!whist) return r->rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
    get(r, "wall_hist", H5T_NATIVE_DOUBLE, (size_t)nwall * nn, (size_t)nh, whist);
    for (int k = 0; k < nwall && !r->rc; k++)
      memcpy(s->wall[k].hist, whist + (size_t)k * nn * nh, nn * (size_t)nh * sizeof *whist);
    free(whist);
  } else {
    double dummy[1];
    get(r, "wall_hist", H5T_NATIVE_DOUBLE, 0, 1, dummy);
  }
  if (r->rc) return r->rc;

  /* neighbour list */
  dem_nlist *nl = &s->nl;
  size_t cp = npairs > 16 ? npairs : 16;
  nl->first = malloc((nn + 1) * sizeof *nl->first);
  nl->nbr = malloc(cp * sizeof *nl->nbr);
  nl->hist = malloc(cp * (size_t)(nh > 0 ? nh : 1) * sizeof *nl->hist);
  nl->touch = malloc(cp);
  if (!nl->first || !nl->nbr || !nl->hist || !nl->touch)
    return r->rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
  nl->cap_rows = nn;
  nl->cap_pairs = cp;
  if (have_list) {
    get(r, "nl_first", H5T_NATIVE_UINT32, nn + 1, 0, nl->first);
  } else {
    uint32_t dummy[1];
    get(r, "nl_first", H5T_NATIVE_UINT32, 0, 0, dummy);
  }
  get(r, "nl_nbr", H5T_NATIVE_UINT32, npairs, 0, nl->nbr);
  get(r, "nl_hist", H5T_NATIVE_DOUBLE, npairs, nh > 0 ? (size_t)nh : 1, nl->hist);
  get(r, "nl_touch", H5T_NATIVE_UINT8, npairs, 0, nl->touch);
  if (r->rc) return r->rc;
  if (have_list) {
    if (nl->first[0] != 0 || nl->first[nn] != npairs)
      return bad(r, "neighbour list end", nl->first[nn], "the pair count");
    for (size_t i = 0; i < nn; i++) {
      if (nl->first[i + 1] < nl->first[i])
        return bad(r, "neighbour list row start", nl->first[i + 1], "non-decreasing");
      for (uint32_t q = nl->first[i]; q < nl->first[i + 1]; q++)
        if (nl->nbr[q] <= i || nl->nbr[q] >= nn)
          return bad(r, "neighbour index", nl->nbr[q], "(row, particles)");
    }
    nl->n = nn;
    nl->npairs = npairs;
  } else {
    nl->n = 0;
    nl->npairs = 0;
  }

  /* user blob */
  size_t ulen = (size_t)mi[MI_USER_LEN];
  unsigned char *ub = malloc(ulen ? ulen : 1);
  if (!ub) return r->rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
  get(r, "user", H5T_NATIVE_UCHAR, ulen, 0, ub);
  uint64_t computed = r->sum.h, stored = 0;
  get(r, "checksum", H5T_NATIVE_UINT64, 1, 0, &stored);
  if (!r->rc && stored != computed)
    r->rc = dem_err_set(err, DEM_EPARSE,
                        "%s: checksum mismatch (stored %016llx, computed %016llx): the file is "
                        "corrupted",
                        path, (unsigned long long)stored, (unsigned long long)computed);
  if (r->rc) {
    free(ub);
    return r->rc;
  }
  if (user) {
    if (ulen) *user = ub;
    else {
      *user = NULL;
      free(ub);
    }
    if (user_len) *user_len = ulen;
  } else {
    free(ub);
  }

  /* scalars and counters */
  if (!(md[MD_DT] >= 0.0) || !(md[MD_SKIN] >= 0.0))
    return r->rc = dem_err_set(err, DEM_EPARSE, "%s: dt = %g s, skin = %g m (allowed >= 0)",
                               path, md[MD_DT], md[MD_SKIN]);
  s->dt = md[MD_DT];
  s->g[0] = md[MD_G0];
  s->g[1] = md[MD_G1];
  s->g[2] = md[MD_G2];
  s->skin = md[MD_SKIN];
  s->nthreads = (int)mi[MI_NTHREADS];
  s->sort_every = (int)mi[MI_SORT_EVERY];
  s->builds_since_sort = (int)mi[MI_BUILDS_SINCE_SORT];
  s->need_build = (int)mi[MI_NEED_BUILD];
  s->need_forces = (int)mi[MI_NEED_FORCES];
  s->last_good = (long)mi[MI_LAST_GOOD];
  s->bd.max_overlap_frac = md[MD_MAX_OVERLAP_FRAC];
  s->bd.check_interval = (int)mi[MI_CHECK_INTERVAL];
  s->bd.ke_growth = md[MD_KE_GROWTH];
  s->bd.ke_strikes = (int)mi[MI_KE_STRIKES];
  s->bd.ke_floor = md[MD_KE_FLOOR];
  if (dem_sim_set_breakdown(s, &s->bd, err))
    return r->rc = dem_err_set(err, DEM_EPARSE, "%s: %s", path, err->msg);
  s->st.steps = (long)mi[MI_STEPS];
  s->st.time = md[MD_TIME];
  s->t_base = md[MD_T_BASE];
  s->steps_base = (long)mi[MI_STEPS_BASE];
  s->st.rebuilds = (long)mi[MI_REBUILDS];
  s->st.sorts = (long)mi[MI_SORTS];
  s->st.contacts = (size_t)mi[MI_CONTACTS];
  s->st.wall_contacts = (size_t)mi[MI_WALL_CONTACTS];
  s->st.max_overlap_frac = md[MD_STAT_MAX_OVERLAP];
  s->st.kinetic_energy = md[MD_KE];
  /* what a build derives: inverses, thread partition, scratch */
  for (size_t i = 0; i < nn; i++) {
    s->invr[i] = 1.0 / p->radius[i];
    s->invm[i] = 1.0 / p->mass[i];
    s->invI[i] = 1.0 / p->inertia[i];
  }
  if (have_list && !s->need_build) {
    dem_engine_partition(s);
    if (dem_engine_spill_reserve(s, err)) return r->rc = err->code;
  } else {
    s->need_build = 1;
  }
  return DEM_OK;
}

dem_sim *dem_sim_checkpoint_read(const char *path, void **user, size_t *user_len,
                                 dem_err *err) {
  if (user) *user = NULL;
  if (user_len) *user_len = 0;
  if (access(path, R_OK) != 0) {
    dem_err_set(err, DEM_EIO, "%s: cannot open checkpoint: %s", path, strerror(errno));
    return NULL;
  }
  H5E_auto2_t old_fn;
  void *old_data;
  H5Eget_auto2(H5E_DEFAULT, &old_fn, &old_data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  rctx r = {.path = path, .err = err, .rc = DEM_OK};
  fnv_init(&r.sum);
  dem_sim *s = NULL;
  r.file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (r.file < 0) {
    r.rc = dem_err_set(err, DEM_EIO,
                       "%s: not a readable HDF5 file (truncated or damaged, or not a "
                       "checkpoint)",
                       path);
  } else {
    restore(&r, &s, user, user_len);
    H5Fclose(r.file);
  }
  H5Eset_auto2(H5E_DEFAULT, old_fn, old_data);
  if (r.rc) {
    dem_sim_free(s);
    if (user && *user) {
      free(*user);
      *user = NULL;
    }
    if (user_len) *user_len = 0;
    return NULL;
  }
  return s;
}
