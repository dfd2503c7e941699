/* AUTO's choice of narrowphase backend from what batches cost on each (issue 46). A backend's time for a batch is
 * modelled as ms = per_pair·pairs + per_cell·cells, fitted by least squares to the batches it ran, each older batch
 * weighing AUTO_DECAY times less, so that the model follows a machine whose load changes. A batch's fixed cost (the
 * GPU's round trip, waking the CPU's threads) has no term: the fit spreads it over the two, and AUTO stays within 5 %
 * of the right choice all the same (tests/c/test_backend_auto.c). The GPU's per-pair cost and the CPU's per-cell
 * cost are what decide: a step of many small pairs stays on the CPU however many cells it has, a few large pairs go
 * to the GPU. Header-only, so that the tests drive it with made-up timings. */
#ifndef PP_BACKEND_AUTO_H
#define PP_BACKEND_AUTO_H

#include <stdbool.h>
#include <stdint.h>

/* A batch under this many cells stays on the CPU without asking the models: the smallest GPU batch (one 16² pair)
 * took 0.43 ms on llvmpipe, the CPU's time for about 20,000 cells. It is also the first GPU batch's size. */
#define AUTO_MIN_CELLS 20000
/* The weight of a fitted batch falls by this much with each later one: about the last 10 batches count. */
#define AUTO_DECAY 0.9
/* One large batch in AUTO_PROBE_EVERY runs on the backend the models did not choose, to keep its model current;
 * never one predicted over AUTO_PROBE_MAX times the chosen's time, so probing costs under 3 % of AUTO's time. */
#define AUTO_PROBE_EVERY 100
#define AUTO_PROBE_MAX 4.0

/* One backend's decayed sums: pairs², pairs·cells, cells², pairs·ms, cells·ms; batches fitted. */
typedef struct backend_fit {
    double pp, pc, cc, pt, ct;
    int32_t batches;
} backend_fit;

typedef struct backend_auto {
    backend_fit fit[2]; /* [0] the CPU, [1] the GPU */
    uint32_t large;     /* large batches decided since the last probe */
} backend_auto;

/* A batch of `pairs` pairs and `cells` cells took ms on the GPU (gpu) or the CPU. */
static inline void backend_auto_learn(backend_auto *a, bool gpu, int32_t pairs, int64_t cells, double ms)
{
    backend_fit *f = &a->fit[gpu];
    const double p = pairs, c = (double)cells;
    f->pp = AUTO_DECAY * f->pp + p * p, f->pc = AUTO_DECAY * f->pc + p * c, f->cc = AUTO_DECAY * f->cc + c * c;
    f->pt = AUTO_DECAY * f->pt + p * ms, f->ct = AUTO_DECAY * f->ct + c * ms;
    f->batches++;
}

/* The fitted per-pair and per-cell costs (ms), where the batches tell them apart and neither is negative; false
 * where they do not (batches of one shape cannot tell a pair's cost from its cells'). */
static inline bool backend_auto_costs(const backend_fit *f, double *per_pair, double *per_cell)
{
    const double det = f->pp * f->cc - f->pc * f->pc;
    if (!(det > 1e-9 * f->pp * f->cc))
        return false;
    *per_pair = (f->pt * f->cc - f->ct * f->pc) / det;
    *per_cell = (f->ct * f->pp - f->pt * f->pc) / det;
    return *per_pair >= 0 && *per_cell >= 0;
}

/* The predicted ms of a batch on the GPU (gpu) or the CPU; negative before that backend ran one. Where the costs
 * are not told apart, the lower of the two costs alone (each fits batches of one shape exactly): optimism that
 * gets the backend tried on another shape, which tells them apart. */
static inline double backend_auto_predict(const backend_auto *a, bool gpu, int32_t pairs, int64_t cells)
{
    const backend_fit *f = &a->fit[gpu];
    if (f->batches == 0)
        return -1;
    double per_pair, per_cell;
    if (backend_auto_costs(f, &per_pair, &per_cell))
        return per_pair * pairs + per_cell * (double)cells;
    const double by_pairs = f->pp > 0 ? f->pt / f->pp * pairs : 0, by_cells = f->cc > 0 ? f->ct / f->cc * (double)cells : 0;
    return by_pairs < by_cells ? by_pairs : by_cells;
}

/* Whether AUTO runs this batch on the GPU (a hardware one is up): small batches never; the first large one does,
 * and the first large one after that on the CPU, so that both models start; then the cheaper, but for a probe. */
static inline bool backend_auto_wants_gpu(backend_auto *a, int32_t pairs, int64_t cells)
{
    if (cells < AUTO_MIN_CELLS)
        return false;
    const double cpu = backend_auto_predict(a, false, pairs, cells), gpu = backend_auto_predict(a, true, pairs, cells);
    if (gpu < 0 || cpu < 0)
        return gpu < 0;
    const bool cheaper = gpu < cpu;
    if (++a->large < AUTO_PROBE_EVERY)
        return cheaper;
    const double chosen = cheaper ? gpu : cpu, other = cheaper ? cpu : gpu;
    if (other > AUTO_PROBE_MAX * chosen)
        return cheaper;
    a->large = 0;
    return !cheaper;
}

#endif
