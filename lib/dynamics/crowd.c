/* The contact budget of crowded bodies. A dynamic body is crowded when it touches more than
 * PP_CROWDED_CONTACT_PAIRS bodies and their overlaps add up to more than twice its solid pixels: a resting
 * pile touches each body along a few thin bands, a spawn into one spot with whole bodies. A pair of two
 * crowded bodies keeps its contacts only if it is among the deepest pairs of one of them, so the solver
 * gets at most PP_CROWDED_CONTACT_PAIRS such pairs a body.
 * The narrowphase is bounded the same way: when a body has more than CROWD_CANDIDATES candidates, each
 * body's best boxes are collided first; the rest are collided after, except those of two bodies the
 * first pass already proved crowded. Nothing is skipped unless a body is proved crowded, so an ordinary
 * scene gets exactly the contacts of one pass. Every choice is made from boxes, contacts (identical on
 * both backends) and body slots, never from memory or thread order. */
#include "crowd.h"
#include "alloc.h"
#include "status.h"
#include "world.h"

/* Overlap, in multiples of a body's solid pixels, past which a body with many pairs is crowded. */
#define CROWD_OVERLAP_RATIO 2

enum { CROWD_FIRST = 1, CROWD_SET_UP = 2 };

static uint32_t slot_a(const pp_contact *c) { return handle_slot(c->a.id); }
static uint32_t slot_b(const pp_contact *c) { return handle_slot(c->b.id); }

/* Bodies the budget may limit: dynamic ones whose contacts always reach the solver. */
static bool eligible(const world *wd, uint32_t slot)
{
    const body *bd = wd->bodies[slot];
    return bd->type == PP_BODY_DYNAMIC && !bd->is_sensor && !bd->one_way;
}

static bool crowded(const world *wd, uint32_t slot)
{
    const crowd_slot *cs = &wd->crowd.slots[slot];
    return eligible(wd, slot) && cs->pairs > PP_CROWDED_CONTACT_PAIRS &&
           cs->overlap > CROWD_OVERLAP_RATIO * wd->bodies[slot]->raster.solid_count;
}

static void reset_slot(world *wd, uint32_t slot) { wd->crowd.slots[slot] = (crowd_slot){.list = -1}; }

/* A new count over the slots (crowd_plan's, crowd_limit_contacts'): every slot is stale until plan_slot resets it. */
static void next_plan(crowd *c)
{
    if (++c->serial == 0) { /* wrapped: no slot may look reset by this count */
        for (int32_t i = 0; i < c->slot_capacity; i++)
            c->slots[i].stamp = 0;
        c->serial = 1;
    }
}

/* A slot as this count found it: reset the first time the count meets it (its stamp is an older count's). */
static crowd_slot *plan_slot(crowd *c, uint32_t slot)
{
    crowd_slot *s = &c->slots[slot];
    if (s->stamp != c->serial)
        *s = (crowd_slot){.list = -1, .stamp = c->serial};
    return s;
}

/* Give a slot a list (room reserved by reserve_lists). */
static void open_list(crowd *c, uint32_t slot)
{
    if (c->slots[slot].list < 0) {
        c->slots[slot].list = c->list_count;
        c->lists[c->list_count++].kept = 0;
    }
}

static pp_status reserve_lists(crowd *c, int32_t n)
{
    c->list_count = 0;
    if (!ARRAY_RESERVE(c->lists, c->list_capacity, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for the contact budget of %d bodies", (int)n);
    return PP_OK;
}

/* Ties between two pairs of body `self` go to the partner nearer in slot, then to the lower: bodies spawned
 * together push their neighbours in creation order apart, not all against the first few. */
static bool partner_before(uint32_t self, uint32_t p, uint32_t q)
{
    const uint32_t dp = p > self ? p - self : self - p, dq = q > self ? q - self : self - q;
    return dp != dq ? dp < dq : p < q;
}

typedef bool (*ranks_before)(const world *wd, uint32_t self, int32_t i, int32_t j);

/* Offer item i to the list of a body's `limit` best, best first. */
static void offer(world *wd, uint32_t self, int32_t i, int32_t limit, ranks_before before)
{
    crowd_list *l = &wd->crowd.lists[wd->crowd.slots[self].list];
    int32_t at = l->kept;
    while (at > 0 && before(wd, self, i, l->best[at - 1]))
        at--;
    if (at >= limit)
        return;
    const int32_t last = l->kept < limit ? l->kept : limit - 1;
    for (int32_t k = last; k > at; k--)
        l->best[k] = l->best[k - 1];
    l->best[at] = i;
    if (l->kept < limit)
        l->kept++;
}

static bool among_best(const world *wd, uint32_t slot, int32_t i)
{
    const int32_t list = wd->crowd.slots[slot].list;
    if (list < 0)
        return false;
    const crowd_list *l = &wd->crowd.lists[list];
    for (int32_t k = 0; k < l->kept; k++)
        if (l->best[k] == i)
            return true;
    return false;
}

/* ---- the narrowphase's two passes ---------------------------------------------------------------- */

static float box_overlap(const world *wd, const bp_pair *pair)
{
    const pp_aabb *p = &wd->awake.proxies[pair->a].box, *q = &wd->awake.proxies[pair->b].box;
    const double w = (p->x1 < q->x1 ? p->x1 : q->x1) - (p->x0 > q->x0 ? p->x0 : q->x0);
    const double h = (p->y1 < q->y1 ? p->y1 : q->y1) - (p->y0 > q->y0 ? p->y0 : q->y0);
    return w > 0 && h > 0 ? (float)(w * h) : 0.0f;
}

/* Candidate i before candidate j among the candidates of `self`: the larger box overlap first. */
static bool box_before(const world *wd, uint32_t self, int32_t i, int32_t j)
{
    const float oi = wd->crowd.box[i], oj = wd->crowd.box[j];
    if (oi != oj)
        return oi > oj;
    const bp_pair *pi = &wd->broad.pairs[i], *pj = &wd->broad.pairs[j];
    return partner_before(self, pi->a == self ? pi->b : pi->a, pj->a == self ? pj->b : pj->a);
}

static bool both_eligible(const world *wd, const bp_pair *p) { return eligible(wd, p->a) && eligible(wd, p->b); }

pp_status crowd_plan(world *wd)
{
    crowd *c = &wd->crowd;
    c->split = false;
    const bp_pair *pairs = wd->broad.pairs;
    const int32_t np = wd->broad.pair_count;
    if (np <= CROWD_CANDIDATES) /* no body can have more */
        return PP_OK;
    pp_status st = world_slot_array_zeroed(wd, (void **)&c->slots, &c->slot_capacity, sizeof *c->slots,
                                           "the contact budget"); /* new slots: stamped by no count */
    if (st)
        return st;
    next_plan(c);
    /* Every pair's slots reset, and the candidates among dynamic bodies counted, in one pass. */
    int32_t many = 0; /* bodies with more than CROWD_CANDIDATES */
    for (int32_t k = 0; k < np; k++) {
        crowd_slot *a = plan_slot(c, pairs[k].a), *b = plan_slot(c, pairs[k].b);
        if (both_eligible(wd, &pairs[k]))
            many += (++a->pairs == CROWD_CANDIDATES + 1) + (++b->pairs == CROWD_CANDIDATES + 1);
    }
    if (many == 0)
        return PP_OK;
    if ((st = reserve_lists(c, many)))
        return st;
    if (!ARRAY_RESERVE(c->pass, c->pass_capacity, np) ||
        !ARRAY_RESERVE(c->box, c->box_capacity, np))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for the contact budget of %d pairs", (int)np);
    for (int32_t k = 0; k < np; k++) {
        if (!both_eligible(wd, &pairs[k]))
            continue;
        c->box[k] = box_overlap(wd, &pairs[k]);
        for (int e = 0; e < 2; e++) {
            const uint32_t s = e ? pairs[k].b : pairs[k].a;
            if (c->slots[s].pairs > CROWD_CANDIDATES) {
                open_list(c, s);
                offer(wd, s, k, CROWD_CANDIDATES, box_before);
            }
        }
    }
    /* A body with few candidates has them all in its first pass. */
    for (int32_t k = 0; k < np; k++) {
        const uint32_t a = pairs[k].a, b = pairs[k].b;
        const bool first = both_eligible(wd, &pairs[k]) &&
                           (c->slots[a].pairs <= CROWD_CANDIDATES || among_best(wd, a, k) ||
                            c->slots[b].pairs <= CROWD_CANDIDATES || among_best(wd, b, k));
        c->pass[k] = first ? CROWD_FIRST : 0;
    }
    c->split = true;
    return PP_OK;
}

bool crowd_wants(const world *wd, int32_t k, int pass)
{
    if (pass == 0)
        return true;
    const crowd *c = &wd->crowd;
    if (pass == 1)
        return c->pass[k] & CROWD_FIRST;
    const bp_pair *p = &wd->broad.pairs[k];
    return !(c->pass[k] & CROWD_FIRST) && !(c->slots[p->a].proven && c->slots[p->b].proven);
}

void crowd_set_up(world *wd, int32_t k) { wd->crowd.pass[k] |= CROWD_SET_UP; }

void crowd_prove(world *wd, int32_t n)
{
    crowd_slot *slots = wd->crowd.slots;
    for (int32_t p = 0; p < 2 * n; p++)
        reset_slot(wd, (uint32_t)wd->batch.bodies[p]);
    for (int32_t p = 0; p < n; p++) {
        if (wd->batch.cores[p].count == 0)
            continue;
        const int64_t pixels = wd->batch.cores[p].count * wd->batch.pairs[p].s * wd->batch.pairs[p].s;
        crowd_slot *a = &slots[wd->batch.bodies[2 * p]], *b = &slots[wd->batch.bodies[2 * p + 1]];
        a->pairs++, b->pairs++;
        a->overlap += pixels, b->overlap += pixels;
    }
    for (int32_t p = 0; p < 2 * n; p++)
        slots[wd->batch.bodies[p]].proven = crowded(wd, (uint32_t)wd->batch.bodies[p]);
}

pp_status crowd_order(world *wd, int32_t first, int32_t n, const int32_t **order)
{
    crowd *c = &wd->crowd;
    if (!ARRAY_RESERVE(c->order, c->order_capacity, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to order %d pairs", (int)n);
    int32_t m = 0, first_at = 0, second_at = first;
    for (int32_t k = 0; k < wd->broad.pair_count; k++)
        if (c->pass[k] & CROWD_SET_UP)
            c->order[m++] = (c->pass[k] & CROWD_FIRST) ? first_at++ : second_at++;
    *order = c->order;
    return PP_OK;
}

/* ---- the solver's budget ------------------------------------------------------------------------- */

static float pair_depth(const world *wd, int32_t i)
{
    float d = wd->contacts[i].depth;
    for (int32_t j = i + 1, end = contact_pair_end(wd, i); j < end; j++)
        d = wd->contacts[j].depth > d ? wd->contacts[j].depth : d;
    return d;
}

/* Pair i before pair j among the pairs of `self`: deeper, then more pixels, then by partner slot. */
static bool contact_before(const world *wd, uint32_t self, int32_t i, int32_t j)
{
    const float di = pair_depth(wd, i), dj = pair_depth(wd, j);
    if (di != dj)
        return di > dj;
    const pp_contact *ci = &wd->contacts[i], *cj = &wd->contacts[j];
    if (ci->pixel_count != cj->pixel_count)
        return ci->pixel_count > cj->pixel_count;
    return partner_before(self, slot_a(ci) == self ? slot_b(ci) : slot_a(ci),
                          slot_a(cj) == self ? slot_b(cj) : slot_a(cj));
}

static bool both_crowded(const world *wd, int32_t i)
{
    return crowded(wd, slot_a(&wd->contacts[i])) && crowded(wd, slot_b(&wd->contacts[i]));
}

pp_status crowd_limit_contacts(world *wd)
{
    if (wd->contact_count <= PP_CROWDED_CONTACT_PAIRS)
        return PP_OK;
    crowd *c = &wd->crowd;
    pp_status st = world_slot_array_zeroed(wd, (void **)&c->slots, &c->slot_capacity, sizeof *c->slots,
                                           "the contact budget"); /* new slots: stamped by no count */
    if (st)
        return st;
    /* Only the slots of this substep's pairs are reset and counted, in one pass, so a large world pays for its
     * contacts alone. Bodies the budget may limit with more than PP_CROWDED_CONTACT_PAIRS pairs: with none, none
     * is crowded (a ground under a row of crates has more, and is never crowded). */
    next_plan(c);
    const contact_run *runs = wd->table.runs;
    int32_t many = 0;
    for (int32_t n = 0; n < wd->table.run_count; n++) {
        const int32_t overlap = wd->contacts[runs[n].first].pixel_count;
        crowd_slot *a = plan_slot(c, runs[n].a), *b = plan_slot(c, runs[n].b);
        many += (++a->pairs == PP_CROWDED_CONTACT_PAIRS + 1 && eligible(wd, runs[n].a)) +
                (++b->pairs == PP_CROWDED_CONTACT_PAIRS + 1 && eligible(wd, runs[n].b));
        a->overlap += overlap, b->overlap += overlap;
    }
    if (many == 0)
        return PP_OK;
    int32_t lists = 0;
    for (int32_t i = 0; i < wd->contact_count; i = contact_pair_end(wd, i))
        lists += both_crowded(wd, i);
    if (lists == 0)
        return PP_OK;
    if ((st = reserve_lists(c, 2 * (int64_t)lists < wd->body_ids.live ? 2 * lists : wd->body_ids.live))) /* bodies with a list */
        return st;
    for (int32_t i = 0; i < wd->contact_count; i = contact_pair_end(wd, i)) {
        if (!both_crowded(wd, i))
            continue;
        for (int e = 0; e < 2; e++) {
            const uint32_t s = e ? slot_b(&wd->contacts[i]) : slot_a(&wd->contacts[i]);
            open_list(c, s);
            offer(wd, s, i, PP_CROWDED_CONTACT_PAIRS, contact_before);
        }
    }
    /* Compact in place: a pair's contacts only move down, over pairs already decided. */
    int32_t n = 0;
    for (int32_t i = 0, end; i < wd->contact_count; i = end) {
        end = contact_pair_end(wd, i);
        if (both_crowded(wd, i) && !among_best(wd, slot_a(&wd->contacts[i]), i) &&
            !among_best(wd, slot_b(&wd->contacts[i]), i))
            continue;
        for (int32_t j = i; j < end; j++)
            wd->contacts[n++] = wd->contacts[j];
    }
    if (n == wd->contact_count)
        return PP_OK;
    wd->contact_count = n;
    return contact_table_list_runs(wd);
}

void crowd_free(crowd *c)
{
    pp_free(c->slots);
    pp_free(c->lists);
    pp_free(c->pass);
    pp_free(c->box);
    pp_free(c->order);
    *c = (crowd){0};
}
