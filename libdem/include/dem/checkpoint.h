/* dem/checkpoint.h — restartable HDF5 checkpoints of the 3-D engine, and interruption.
 *
 * A checkpoint holds the complete state that determines the rest of a trajectory: the
 * particle arrays (in the engine's current order), the materials and interactions (law
 * name, a signature of the law's table, the compiled coefficient array), the walls (spec,
 * position, velocity, servo state, loads, work, wall lists and histories), the neighbour
 * list as it stands (pair keys, history blocks, the positions at the last build), the
 * counters (steps, time, builds since the last sort), dt, gravity, skin, thread count and
 * breakdown thresholds, plus an opaque caller blob (stage name, RNG state, ...).
 * Because the neighbour list is stored rather than rebuilt, writing a checkpoint does not
 * disturb the running simulation, and a simulation read back continues bit-identically
 * (same thread count) to the one that was never stopped. See docs/engine.md.
 *
 * Files are written to a temporary name and renamed; a checksum over all arrays detects
 * corruption. HDF5 stays inside libdem/src/engine/checkpoint.c.
 */
#ifndef DEM_CHECKPOINT_H
#define DEM_CHECKPOINT_H

#include <signal.h>
#include <stddef.h>

#include "dem/engine.h"
#include "dem/error.h"

/* 2: wall records hold dem_wall_spec.length and .angle (finite indenters); the clock base
 * (time = t_base + (steps - steps_base) dt, exact across split runs).
 * 3: wall records hold the normal dashpots' part of the wall load (a servo's input). */
#define DEM_CHECKPOINT_VERSION 3

/* Write the state of s and the caller's blob user[0 .. user_len) (may be NULL / 0) to path
 * (via path.tmpPID and rename). s is not modified. */
int dem_sim_checkpoint_write(const dem_sim *s, const char *path, const void *user,
                             size_t user_len, dem_err *err);

/* Read a checkpoint into a new simulation. If user is not NULL, *user receives a malloc'd
 * copy of the blob (free it; NULL if empty) and *user_len its length. Errors (NULL return,
 * err set, naming the file): DEM_EIO (missing or unreadable file, truncated or not HDF5),
 * DEM_EPARSE (missing dataset, wrong sizes or values, checksum mismatch), DEM_EUNSUPPORTED
 * (other format version), DEM_ENOTFOUND (unknown law), DEM_EINVAL (the law's table differs
 * from the one that wrote the file).
 * The simulation comes back with its thread count; calling dem_sim_set_threads with the
 * same count keeps the stored neighbour list (a different count, or dem_sim_set_skin,
 * dem_sim_set_gravity, dem_sim_invalidate, adding particles or walls, starts afresh at the
 * next step: still correct, no longer bit-identical to the uninterrupted run). */
dem_sim *dem_sim_checkpoint_read(const char *path, void **user, size_t *user_len,
                                 dem_err *err);

/* Interruption: dem_sim_run polls *flag (e.g. set by a SIGINT/SIGTERM handler) once per
 * step; when it is non-zero the run returns DEM_EINTERRUPTED after completing the current
 * step (or at once, with no step taken, if it is set on entry). The state is then a clean
 * step boundary: write a checkpoint and exit. NULL switches polling off. The flag stays
 * set: the caller clears it. */
void dem_sim_set_interrupt_flag(dem_sim *s, volatile sig_atomic_t *flag);

/* The step count at the last breakdown check that passed (finite kinetic energy, no
 * strike limit reached; every bd.check_interval steps), or -1 if none yet. After
 * DEM_ENONFINITE / DEM_EUNSTABLE / DEM_ERUNAWAY the state in memory is the broken one:
 * restart from the last checkpoint written (write them at least at stage boundaries), and
 * optionally write the broken state under another name for diagnosis. */
long dem_sim_last_good_step(const dem_sim *s);

#endif
