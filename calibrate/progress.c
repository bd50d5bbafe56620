/* The progress line: evaluations, best objective, elapsed time and an ETA from the maxeval
 * budget. On a terminal it is rewritten in place (\r) at most 10 times a second; otherwise
 * a plain line is printed every 10 s, so logs stay readable. */
#include <stdio.h>
#include <time.h>
#include <unistd.h>

#include "cal.h"

double cal_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double last_print = -1.0;
static int line_open = 0;

void cal_progress_stderr(const cal_problem *p, void *user) {
  (void)user;
  int tty = isatty(fileno(stderr));
  double now = cal_now(), el = now - p->t0;
  if (last_print >= 0.0 && now - last_print < (tty ? 0.1 : 10.0)) return;
  last_print = now;
  long done = p->nevals;
  double eta = done > 0 && p->maxeval_total > done ? el / done * (p->maxeval_total - done) : 0.0;
  fprintf(stderr, "%s%s: eval %ld/%d (%ld cached, %ld failed), best S = %.6g, %.1f s, ETA <= %.0f s%s",
          tty ? "\r" : "", p->cfg->name, done, p->maxeval_total, p->ncached, p->nfailed,
          p->best_f, el, eta, tty ? "   " : "\n");
  if (tty) line_open = 1;
  fflush(stderr);
}

void cal_progress_end(void) {
  if (line_open) fputc('\n', stderr);
  line_open = 0;
  last_print = -1.0;
}
