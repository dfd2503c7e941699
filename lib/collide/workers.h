/* A world's narrowphase workers: threads that share a batch of pairs' work (their set-up, CPU cores, contacts), each
 * pair's written to its own slots. */
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

/* Below this many pairs a batch's per-pair host work runs on the calling thread. It costs 1.6 k (set-up) and 2.9 k
 * (contacts) instructions a pair, about 1–2 µs, against a thread wake-up's 30–40 µs: a hundred pairs pays for the
 * wake-ups on many cores. On 2 cores sharing it measured a wash (tests/bench/README.md, Worker threads). */
#define WORKERS_MIN_PAIRS 128
/* Items a thread takes at a time in that work: pairs cost alike there, and fewer turns of the shared counter. */
#define WORKERS_GRAIN 16

/* One item of a shared batch: item k, with the scratch of the thread that took it. */
typedef pp_status (*workers_task)(void *user, int32_t k, np_scratch *scratch);

/* task on items [0, n), shared over `threads` threads, the calling one included (its scratch is `scratch`),
 * `grain` items at a time; *used says how many ran. The pool in *pool is started on first use and kept. Each item
 * must write only its own slots, so that the result does not depend on the sharing; a task on a worker thread
 * must not allocate. The first failing item's status and message are returned. */
pp_status workers_for(np_workers **pool, int32_t threads, int32_t n, int32_t grain, workers_task task, void *user,
                      np_scratch *scratch, int32_t *used);

/* narrow_cpu_core on pairs[0, n) into cores[0, n), shared over `threads` threads, the calling one
 * included (its scratch is `scratch`); *used says how many ran. The pool in *pool is started on
 * first use and kept. Each pair writes only its own core, so the result does not depend on the sharing. */
pp_status workers_run(np_workers **pool, int32_t threads, const np_settings *set, const np_pair *pairs, int32_t n,
                      np_scratch *scratch, np_core *cores, int32_t *used);

/* Stop and join the threads; NULL is fine. */
void workers_free(np_workers *pool);

#endif
