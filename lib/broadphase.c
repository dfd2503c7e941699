/* Sweep-and-prune on x over the live bodies' world AABBs. The order array persists between
 * steps, so the insertion sort runs in near-linear time on a scene that moves a little. */
#include "alloc.h"
#include "broadphase.h"
#include "status.h"

#include <stdlib.h>

static pp_status grow(void **buf, int32_t *cap, int32_t need, size_t item)
{
    if (need <= *cap)
        return PP_OK;
    int32_t n = *cap ? *cap : 64;
    while (n < need)
        n *= 2;
    void *p = pp_realloc(*buf, (size_t)n * item);
    if (!p)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for %d entries", (int)n);
    *buf = p;
    *cap = n;
    return PP_OK;
}

static bool before(const bp_proxy *p, uint32_t a, uint32_t b)
{
    return p[a].box.x0 < p[b].box.x0 || (p[a].box.x0 == p[b].box.x0 && a < b);
}

/* `roused` marks sleeping bodies that share a pair with an awake one (NULL in the first sweep). */
static bool may_touch(const bp_proxy *p, const bp_proxy *q, const uint8_t *roused, uint32_t ip, uint32_t iq)
{
    if (!p->dynamic && !q->dynamic)
        return false; /* static and kinematic never respond to each other */
    if (roused) {
        /* Second sweep: only a roused sleeper's pairs with static bodies. */
        if (!((roused[ip] && !q->movable) || (roused[iq] && !p->movable)))
            return false;
    } else if (!p->awake && !q->awake) {
        return false;
    }
    if (!(p->category_bits & q->mask_bits) || !(q->category_bits & p->mask_bits))
        return false;
    return p->box.y0 <= q->box.y1 && q->box.y0 <= p->box.y1;
}

/* Append the pairs of the sorted order that may touch. */
static pp_status sweep(pp_broadphase *bp, const bp_proxy *proxies, const uint8_t *roused)
{
    for (int32_t i = 0; i < bp->order_count; i++) {
        const uint32_t ip = bp->order[i];
        const bp_proxy *p = &proxies[ip];
        for (int32_t j = i + 1; j < bp->order_count; j++) {
            const uint32_t iq = bp->order[j];
            const bp_proxy *q = &proxies[iq];
            if (q->box.x0 > p->box.x1)
                break;
            if (!may_touch(p, q, roused, ip, iq))
                continue;
            pp_status st = grow((void **)&bp->pairs, &bp->pair_cap, bp->pair_count + 1, sizeof(bp_pair));
            if (st)
                return st;
            bp->pairs[bp->pair_count++] = ip < iq ? (bp_pair){ip, iq} : (bp_pair){iq, ip};
        }
    }
    return PP_OK;
}

/* A sleeping body paired with an awake one may be woken by ODE through their contact joint in this
 * very step, and would then move with nothing under it: the broadphase skipped its pairs with static
 * bodies while it slept. Such a sleeper gets those pairs too (its other sleeping neighbours stay out). */
static pp_status rouse_sleepers(pp_broadphase *bp, const bp_proxy *proxies, int32_t n)
{
    uint8_t *roused = NULL;
    for (int32_t k = 0; k < bp->pair_count; k++) {
        const uint32_t a = bp->pairs[k].a, b = bp->pairs[k].b;
        const uint32_t sleeper = proxies[a].awake ? b : a, other = sleeper == a ? b : a;
        if (!proxies[other].awake || proxies[sleeper].awake || !proxies[sleeper].dynamic)
            continue;
        if (!roused && !(roused = pp_calloc((size_t)n, 1)))
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory");
        roused[sleeper] = 1;
    }
    if (!roused)
        return PP_OK;
    const pp_status st = sweep(bp, proxies, roused);
    pp_free(roused);
    return st;
}

pp_status broadphase_find_pairs(pp_broadphase *bp, const bp_proxy *proxies, int32_t n)
{
    /* Rebuild the order from the previous one: keep live slots, append new ones. */
    pp_status st = grow((void **)&bp->order, &bp->order_cap, n, sizeof(uint32_t));
    if (st)
        return st;
    int32_t m = 0;
    for (int32_t i = 0; i < bp->order_count; i++) {
        const uint32_t s = bp->order[i];
        if ((int32_t)s < n && proxies[s].live)
            bp->order[m++] = s;
    }
    /* Slots that were not in the order yet are those not seen; mark with a bitmap. */
    uint8_t *seen = pp_calloc((size_t)n + 1, 1);
    if (!seen)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory");
    for (int32_t i = 0; i < m; i++)
        seen[bp->order[i]] = 1;
    for (int32_t s = 0; s < n; s++)
        if (proxies[s].live && !seen[s])
            bp->order[m++] = (uint32_t)s;
    pp_free(seen);
    bp->order_count = m;

    for (int32_t i = 1; i < m; i++) {
        const uint32_t key = bp->order[i];
        int32_t j = i - 1;
        while (j >= 0 && before(proxies, key, bp->order[j])) {
            bp->order[j + 1] = bp->order[j];
            j--;
        }
        bp->order[j + 1] = key;
    }

    bp->pair_count = 0;
    st = sweep(bp, proxies, NULL);
    return st ? st : rouse_sleepers(bp, proxies, n);
}

void broadphase_free(pp_broadphase *bp)
{
    pp_free(bp->order);
    pp_free(bp->pairs);
    *bp = (pp_broadphase){0};
}
