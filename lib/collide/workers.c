/* Narrowphase pairs are independent: each pair's set-up, core and contacts read the bodies and write the pair's own
 * slot. A batch is shared out through an atomic counter, `grain` items at a time (pair costs differ by orders of
 * magnitude, so fixed slices would leave threads idle), the calling thread working too. Threads start on the first
 * batch big enough to need them, so a small scene never has any. */
#include "alloc.h"
#include "workers.h"
#include "status.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#define WORKERS_MAX 16

struct np_workers {
    int32_t count;                  /* threads besides the caller */
    pthread_t *threads;
    np_scratch *scratch;            /* one per thread */
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    uint64_t batch;                 /* bumped for each batch; a thread runs each batch once */
    int32_t running;                /* threads still on the current batch */
    bool quit;
    /* The current batch. */
    workers_task task;
    void *user;
    int32_t n, grain;
    atomic_int next;                /* the next item to take */
    pp_status status;               /* the first failure, and its message */
    char message[256];
};

int32_t workers_wanted(int32_t worker_threads)
{
    if (worker_threads > 0)
        return worker_threads;
    const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    return cpus < 1 ? 1 : cpus > WORKERS_MAX ? WORKERS_MAX : (int32_t)cpus;
}

/* Take items until none are left; the first failure stops every thread. */
static void run_items(np_workers *w, np_scratch *scratch)
{
    for (;;) {
        const int32_t from = atomic_fetch_add(&w->next, w->grain);
        if (from >= w->n)
            return;
        const int32_t to = w->n - from < w->grain ? w->n : from + w->grain;
        for (int32_t k = from; k < to; k++) {
            const pp_status st = w->task(w->user, k, scratch);
            if (st) {
                pthread_mutex_lock(&w->lock);
                if (!w->status) {
                    w->status = st;
                    snprintf(w->message, sizeof w->message, "%s", pp_last_error());
                }
                pthread_mutex_unlock(&w->lock);
                atomic_store(&w->next, w->n);
                return;
            }
        }
    }
}

typedef struct worker_arg {
    np_workers *pool;
    int32_t index;
} worker_arg;

static void *worker_main(void *arg)
{
    worker_arg *a = arg;
    np_workers *w = a->pool;
    np_scratch *scratch = &w->scratch[a->index];
    pp_free(a);
    uint64_t seen = 0;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (w->batch == seen && !w->quit)
            pthread_cond_wait(&w->wake, &w->lock);
        if (w->quit)
            break;
        seen = w->batch;
        pthread_mutex_unlock(&w->lock);
        run_items(w, scratch);
        pthread_mutex_lock(&w->lock);
        if (--w->running == 0)
            pthread_cond_signal(&w->done);
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

static pp_status workers_start(np_workers **pool, int32_t count)
{
    np_workers *w = pp_calloc(1, sizeof *w);
    if (!w)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for narrowphase workers");
    w->threads = pp_calloc((size_t)count, sizeof *w->threads);
    w->scratch = pp_calloc((size_t)count, sizeof *w->scratch);
    if (!w->threads || !w->scratch) {
        pp_free(w->threads);
        pp_free(w->scratch);
        pp_free(w);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for narrowphase workers");
    }
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->wake, NULL);
    pthread_cond_init(&w->done, NULL);
    for (int32_t i = 0; i < count; i++) {
        worker_arg *a = pp_malloc(sizeof *a);
        if (!a) { /* nothing kept: the next batch tries again */
            workers_free(w);
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for narrowphase workers");
        }
        *a = (worker_arg){w, i};
        if (pthread_create(&w->threads[i], NULL, worker_main, a) != 0) {
            pp_free(a);
            break; /* the system would start no more: run with the threads that did start */
        }
        w->count++;
    }
    *pool = w;
    return PP_OK;
}

pp_status workers_for(np_workers **pool, int32_t threads, int32_t n, int32_t grain, workers_task task, void *user,
                      np_scratch *scratch, int32_t *used)
{
    *used = n > 0;
    if (threads > 1 && !*pool) {
        pp_status st = workers_start(pool, threads - 1);
        if (st)
            return st;
    }
    np_workers *w = *pool;
    if (threads <= 1 || !w || w->count == 0 || n <= grain) {
        for (int32_t k = 0; k < n; k++) {
            pp_status st = task(user, k, scratch);
            if (st)
                return st;
        }
        return PP_OK;
    }
    *used = 1 + w->count;
    pthread_mutex_lock(&w->lock);
    w->task = task, w->user = user, w->n = n, w->grain = grain;
    atomic_store(&w->next, 0);
    w->status = PP_OK;
    w->running = w->count;
    w->batch++;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);

    run_items(w, scratch);

    pthread_mutex_lock(&w->lock);
    while (w->running > 0)
        pthread_cond_wait(&w->done, &w->lock);
    const pp_status st = w->status;
    pthread_mutex_unlock(&w->lock);
    /* The message was recorded on the thread that failed; repeat it on the caller's. */
    return st ? pp_fail(st, "%s", w->message) : PP_OK;
}

typedef struct core_batch {
    const np_settings *set;
    const np_pair *pairs;
    np_core *cores;
} core_batch;

static pp_status run_core(void *user, int32_t k, np_scratch *scratch)
{
    const core_batch *b = user;
    return narrow_cpu_core(b->set, &b->pairs[k], scratch, &b->cores[k]);
}

pp_status workers_run(np_workers **pool, int32_t threads, const np_settings *set, const np_pair *pairs, int32_t n,
                      np_scratch *scratch, np_core *cores, int32_t *used)
{
    if (threads > 1 && !*pool) {
        pp_status st = workers_start(pool, threads - 1);
        if (st)
            return st;
    }
    /* Worker threads never allocate: every scratch is grown here, on the calling thread, for the
     * batch's largest pair, so a failure is reported here and the count of allocations is fixed. */
    if (threads > 1 && *pool) {
        int32_t nx = 0, ny = 0;
        for (int32_t k = 0; k < n; k++)
            nx = pairs[k].nx > nx ? pairs[k].nx : nx, ny = pairs[k].ny > ny ? pairs[k].ny : ny;
        pp_status st = np_scratch_reserve(scratch, nx, ny);
        for (int32_t i = 0; i < (*pool)->count && !st; i++)
            st = np_scratch_reserve(&(*pool)->scratch[i], nx, ny);
        if (st)
            return st;
    }
    core_batch b = {set, pairs, cores};
    return workers_for(pool, threads, n, 1, run_core, &b, scratch, used);
}

void workers_free(np_workers *w)
{
    if (!w)
        return;
    pthread_mutex_lock(&w->lock);
    w->quit = true;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);
    for (int32_t i = 0; i < w->count; i++) {
        pthread_join(w->threads[i], NULL);
        np_scratch_free(&w->scratch[i]);
    }
    pthread_mutex_destroy(&w->lock);
    pthread_cond_destroy(&w->wake);
    pthread_cond_destroy(&w->done);
    pp_free(w->threads);
    pp_free(w->scratch);
    pp_free(w);
}
