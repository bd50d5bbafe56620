/* dem/error.h — status codes and error messages of libdem.
 *
 * Every fallible libdem function returns an int status (DEM_OK == 0, failures > 0),
 * the way GSL does; none aborts, so the library can live inside an optimiser.
 * Functions that can say more take a `dem_err *` (may be NULL) and write a message
 * that names the offending field, its value and the allowed range.
 * The codes and their messages are written once, in the X-macro below.
 */
#ifndef DEM_ERROR_H
#define DEM_ERROR_H

#include <stddef.h>

#define DEM_ERROR_LIST(X)                                                     \
  X(DEM_OK, 0, "success")                                                     \
  X(DEM_EINVAL, 1, "invalid argument")                                        \
  X(DEM_ERANGE, 2, "value outside its allowed range")                         \
  X(DEM_ENOMEM, 3, "out of memory")                                           \
  X(DEM_EIO, 4, "input/output error")                                         \
  X(DEM_EPARSE, 5, "malformed input")                                         \
  X(DEM_ENOTFOUND, 6, "unknown name")                                         \
  X(DEM_ENONFINITE, 7, "non-finite value (NaN or infinity)")                  \
  X(DEM_EUNSTABLE, 8, "numerical instability (time step too large?)")         \
  X(DEM_ERUNAWAY, 9, "runaway overlap")                                       \
  X(DEM_EMAXITER, 10, "iteration limit reached")                              \
  X(DEM_EUNSUPPORTED, 11, "unsupported combination")                          \
  X(DEM_EMISSING, 12, "required value missing")                               \
  X(DEM_EPHYSICS, 13, "physically impossible parameter set")                  \
  X(DEM_EINTERRUPTED, 14, "interrupted")

enum dem_status {
#define DEM_X_ENUM(name, code, msg) name = code,
  DEM_ERROR_LIST(DEM_X_ENUM)
#undef DEM_X_ENUM
};

#define DEM_ERRMSG_LEN 512

/* A status with its detailed message. Zero-initialise before use. */
typedef struct dem_err {
  int code;
  char msg[DEM_ERRMSG_LEN];
} dem_err;

/* Short text of a status code; never NULL. */
const char *dem_strerror(int status);

/* Record `code` and a printf-style message in err (if err != NULL); returns code,
 * so that `return dem_err_set(err, DEM_ERANGE, "...")` reads naturally. */
int dem_err_set(dem_err *err, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Prefix the message already in err with more context ("file.cfg:12: ..."). */
void dem_err_prefix(dem_err *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#endif
