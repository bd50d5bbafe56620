/* Particle snapshots as HDF5 (one file per snapshot) and an XDMF index for ParaView.
 *
 * snap_NNNNNN.h5: datasets x [n x 3] (m), v [n x 3] (m/s), omega [n x 3] (rad/s),
 * radius [n] (m), id [n]; attributes time (s) and stage. Each file and the XDMF index are
 * written to a temporary name and renamed when complete. The XDMF file is a temporal
 * collection of Polyvertex grids (one per snapshot) reading the HDF5 datasets.
 */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

static int put(hid_t f, const char *name, hid_t type, int rank, const hsize_t *dims,
               const void *data) {
  hid_t sp = H5Screate_simple(rank, dims, NULL);
  hid_t ds = H5Dcreate2(f, name, type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t e = ds < 0 ? -1 : H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(sp);
  return e < 0 ? -1 : 0;
}

int dem_scene_write_snapshot(dem_sim *s, const char *dir, int index, double t,
                             const char *stage, dem_err *err) {
  dem_particles *p = dem_sim_particles(s);
  char path[1024], tmp[1100];
  snprintf(path, sizeof path, "%s/snap_%06d.h5", dir, index);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) return dem_err_set(err, DEM_EIO, "snapshot: cannot create %s", tmp);
  hsize_t d2[2] = {p->n, 3}, d1[1] = {p->n};
  int bad = put(f, "x", H5T_NATIVE_DOUBLE, 2, d2, p->x) ||
            put(f, "v", H5T_NATIVE_DOUBLE, 2, d2, p->v) ||
            put(f, "omega", H5T_NATIVE_DOUBLE, 2, d2, p->omega) ||
            put(f, "radius", H5T_NATIVE_DOUBLE, 1, d1, p->radius) ||
            put(f, "id", H5T_NATIVE_UINT32, 1, d1, p->id);
  hid_t as = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(f, "time", H5T_NATIVE_DOUBLE, as, H5P_DEFAULT, H5P_DEFAULT);
  bad |= a < 0 || H5Awrite(a, H5T_NATIVE_DOUBLE, &t) < 0;
  if (a >= 0) H5Aclose(a);
  hid_t st = H5Tcopy(H5T_C_S1);
  H5Tset_size(st, strlen(stage) + 1);
  a = H5Acreate2(f, "stage", st, as, H5P_DEFAULT, H5P_DEFAULT);
  bad |= a < 0 || H5Awrite(a, st, stage) < 0;
  if (a >= 0) H5Aclose(a);
  H5Tclose(st);
  H5Sclose(as);
  bad |= H5Fclose(f) < 0;
  if (bad || rename(tmp, path) != 0) {
    remove(tmp);
    return dem_err_set(err, DEM_EIO, "snapshot: writing %s failed", path);
  }
  return DEM_OK;
}

int dem_scene_write_xdmf(const char *dir, int count, const double *times, const size_t *n,
                         dem_err *err) {
  char path[1024], tmp[1100];
  snprintf(path, sizeof path, "%s/snapshots.xmf", dir);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *fp = fopen(tmp, "w");
  if (!fp) return dem_err_set(err, DEM_EIO, "xdmf: cannot create %s", tmp);
  fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
              "<Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (int k = 0; k < count; k++) {
    const char *h = "snap_";
    fprintf(fp, " <Grid Name=\"s%d\" GridType=\"Uniform\">\n  <Time Value=\"%.9g\"/>\n", k,
            times[k]);
    fprintf(fp, "  <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%zu\"/>\n", n[k]);
    fprintf(fp, "  <Geometry GeometryType=\"XYZ\"><DataItem Dimensions=\"%zu 3\" "
                "NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s%06d.h5:/x</DataItem>"
                "</Geometry>\n", n[k], h, k);
    fprintf(fp, "  <Attribute Name=\"radius\" AttributeType=\"Scalar\" Center=\"Node\">"
                "<DataItem Dimensions=\"%zu\" NumberType=\"Float\" Precision=\"8\" "
                "Format=\"HDF\">%s%06d.h5:/radius</DataItem></Attribute>\n", n[k], h, k);
    fprintf(fp, "  <Attribute Name=\"v\" AttributeType=\"Vector\" Center=\"Node\">"
                "<DataItem Dimensions=\"%zu 3\" NumberType=\"Float\" Precision=\"8\" "
                "Format=\"HDF\">%s%06d.h5:/v</DataItem></Attribute>\n", n[k], h, k);
    fprintf(fp, " </Grid>\n");
  }
  fprintf(fp, "</Grid>\n</Domain>\n</Xdmf>\n");
  if (fclose(fp) != 0 || rename(tmp, path) != 0) {
    remove(tmp);
    return dem_err_set(err, DEM_EIO, "xdmf: writing %s failed", path);
  }
  return DEM_OK;
}
