/* A world's narrowphase workers: threads that run the CPU cores of one batch of pairs. */
#ifndef PP_WORKERS_H
#define PP_WORKERS_H

#include "narrowphase.h"

/* Below this many grid cells a batch runs on the calling thread. Measured on 2 cores: sharing a
 * batch costs 30–40 µs (waking a thread), so it loses below about 75 µs of work (4 pairs of 512 px
 * crates, 18,000 cells, took 80 µs alone and longer shared), breaks even at 100 pairs of 12 px
 * crates, and gains a third from 300. */
#define WORKERS_MIN_CELLS 32768

typedef struct np_workers np_workers;

/* Threads `worker_threads` asks for: itself, or one per online CPU (at most 16) for 0. */
int32_t workers_wanted(int32_t worker_threads);

/* narrow_cpu_core on pairs[0, n) into cores[0, n), shared over `threads` threads, the calling one
 * included (its scratch is `scratch`); *used says how many ran. The pool in *pool is started on
 * first use and kept. Each pair writes only its own core, so the result does not depend on the sharing. */
pp_status workers_run(np_workers **pool, int32_t threads, const np_settings *set, const np_pair *pairs, int32_t n,
                      np_scratch *scratch, np_core *cores, int32_t *used);

/* Stop and join the threads; NULL is fine. */
void workers_free(np_workers *pool);

#endif
