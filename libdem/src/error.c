/* Status codes and messages (dem/error.h). */
#include "dem/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *dem_strerror(int status) {
  switch (status) {
#define DEM_X_CASE(name, code, msg) \
  case code:                        \
    return msg;
    DEM_ERROR_LIST(DEM_X_CASE)
#undef DEM_X_CASE
  default:
    return "unknown status code";
  }
}

int dem_err_set(dem_err *err, int code, const char *fmt, ...) {
  if (err) {
    va_list ap;
    va_start(ap, fmt);
    err->code = code;
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
  }
  return code;
}

void dem_err_prefix(dem_err *err, const char *fmt, ...) {
  if (!err) return;
  char head[DEM_ERRMSG_LEN], old[DEM_ERRMSG_LEN];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(head, sizeof head, fmt, ap);
  va_end(ap);
  memcpy(old, err->msg, sizeof old);
  size_t h = strlen(head);
  if (h >= sizeof err->msg) h = sizeof err->msg - 1;
  memcpy(err->msg, head, h);
  size_t rest = sizeof err->msg - 1 - h, o = strnlen(old, sizeof old);
  if (o > rest) o = rest;
  memcpy(err->msg + h, old, o);
  err->msg[h + o] = '\0';
}
