/* Islands: which bodies solve together and which sleep together. ODE steps one method per world, so the
 * islands are chosen here and solver_step hides the others while each method runs. An island is what ODE's
 * own walk will find: bodies with ODE bodies (dynamic or kinematic) joined by contacts; static bodies join
 * nothing. The exact solver takes an island of two or more dynamic bodies (where QuickStep's unfinished
 * solve lets stacks sag, creep and crush light bodies) up to exact_island_rows, and a lone dynamic body
 * without joints: its few rows cost dWorldStep less than QuickStep's sweeps (the destruction scene's ODE
 * time fell by a third). A lone body on joints stays QuickStep's, whose soft joints the tests were tuned on.
 * Both passes visit only the substep's nodes: the awake set's movable bodies and the contacts' movable
 * bodies (a sleeper touched by an awake body). A sleeping island is never visited. */
#include "alloc.h"
#include "island.h"
#include "awake.h"
#include "carry.h"
#include "joint.h"

/* Constraint rows a contact costs (the normal and one in-plane friction row), and at most a joint's. */
enum { ROWS_PER_CONTACT = 2, ROWS_PER_FIXED_ROTATION = 4, ROWS_PER_JOINT = 6 };

/* What an island holds, for its span: a joint (whose springs are tuned to one substep), a body pressing on
 * one over HARD_MASS_RATIO times lighter (QuickStep at twice the time step let a 1:10:100:1000 chain fall) or
 * a kinematic body (an island that sat a substep out and then solved one lost that substep of the body's
 * prescribed motion: a frame turning at 25°/s round 50 tumbling boxes strayed 0.53 rad in 10 s), all solved
 * every substep; an awake body that sat the last substep out, and one that did not; a body a collided pair
 * touched this step, or whose stack pair moved past a pile at rest (carry_struck, carry_restless: the island is
 * not at rest); a contact; a pair the narrowphase found touching this step (carry_was_collided: a lone body with
 * contacts and none collided is at rest); past the
 * step's first substep, carry_struck whatever the substep knows (ROOT_HIT: a resting lone body keeps sitting
 * out); an awake body that sat out fewer than the three substeps before (ROOT_SHORT: no span of four). */
enum { ROOT_EVERY_SUBSTEP = 1, ROOT_BEHIND = 2, ROOT_CURRENT = 4, ROOT_STRUCK = 8, ROOT_TOUCHING = 16,
       ROOT_COLLIDED = 32, ROOT_HIT = 64, ROOT_SHORT = 128, ROOT_SLANT = 256 };
/* The span ROOT_* flags decide; ROOT_STRUCK also chooses the iterations. A slanted face (ROOT_SLANT, see
 * island_slanted_face) keeps a stack off a span of four. */
#define ROOT_SPAN_FLAGS (ROOT_EVERY_SUBSTEP | ROOT_BEHIND | ROOT_CURRENT)
enum { HARD_MASS_RATIO = 4 };
/* island_set.every's bits. */
enum { EVERY_SUBSTEP = 1, EVERY_SLANT = 2 };

/* Past this mass ratio between two bodies of an island, the exact solver's factorisation loses its pivots and
 * ODE aborts the process (dxLDLTRemove's or dxNormalize4's assertion: a 16 px crate of density 1e-13 under
 * one of 1) where QuickStep only answers loosely: such an island is QuickStep's. 1000:1 stacks stand exactly. */
#define EXACT_MASS_RATIO 1e6

/* Why an island is not solved exactly: a mass ratio past EXACT_MASS_RATIO or a body out of reach (never); for a
 * lone body (unless exact_solver asks for every island), a joint, no dynamic body (a kinematic one alone, or one
 * out of reach), or a bitmap one pixel thin, whose contact points lie within a pixel: the exact LCP's rows are
 * then nearly dependent, and a 1×1 grain dropped 100 px spun at 280 rad/s and rested 2.1 px deep. */
enum { NOT_EXACT = 1, NOT_EXACT_ALONE = 2, NOT_EXACT_SLANT = 4 };

/* A pair whose two points lie more than SLANT_FACE_PX apart on a face off both bodies' bitmap axes (by more
 * than SLANT_SIN) keeps its stack off the exact solver, unless exact_solver asks for it. Such a face is a
 * staircase of pixels on both sides: the exact solve put a joint's whole load on one end of it (an arch's
 * keystone joint, 249,006 against 0), the block turned about that end, the joint's other end opened by under
 * a pixel and left the raster, and Box2D v3's arch (130-200 px joints) became a mechanism at 0.4 s. QuickStep
 * spreads the load and stands it. Faces along a body's axes (a tower of crates of any size, whose exact solve
 * holds 20 high where QuickStep drops it) and short ones (16-32 px boxes, cards) stay exact. */
#define SLANT_FACE_PX 64.0
#define SLANT_SIN 0.0348994967025010 /* sin 2° */

/* Whether normal n lies off both of bd's bitmap axes by more than SLANT_SIN. */
static bool off_axes(const body *bd, dvec2 n)
{
    const dvec2 u = dv_unrot(n, bd->cos_a, bd->sin_a);
    return fabs(u.x) > SLANT_SIN && fabs(u.y) > SLANT_SIN;
}

bool island_slanted_face(const world *wd, int32_t k, int32_t end)
{
    if (end - k != 2)
        return false;
    const pp_contact *c = &wd->contacts[k];
    const dvec2 n = dv(c->normal.x, c->normal.y);
    const dvec2 d = dv(c[1].point.x - c->point.x, c[1].point.y - c->point.y);
    return dv_dot(d, d) > SLANT_FACE_PX * SLANT_FACE_PX && off_axes(body_of(wd, c->a), n) &&
           off_axes(body_of(wd, c->b), n);
}

static bool within_reach(const world *wd, const body *bd)
{
    const double reach = 1.0 + (double)bd->raster.width + (double)bd->raster.height;
    const dvec2 off = dv_sub(solver_body_get_com(wd->solver, &bd->sb), body_com_world(bd));
    return dv_dot(off, off) <= reach * reach;
}

static bool is_node(const world *wd, const body *bd)
{
    return bd && bd->sb.body && wd->islands.node_mark[bd->index] == wd->islands.node_pass;
}

/* Make a movable body a node of this pass (once): its own root, value 0. */
static void add_node(world *wd, const body *bd)
{
    const int32_t i = (int32_t)bd->index;
    if (!bd->sb.body || wd->islands.node_mark[i] == wd->islands.node_pass)
        return;
    wd->islands.node_mark[i] = wd->islands.node_pass;
    wd->islands.nodes[wd->islands.node_count++] = i;
}

/* Both bodies of a joint with an ODE body on each side, or false. */
static bool joint_movers(const world *wd, const joint *jt, const body **a, const body **b)
{
    *a = jt ? joint_body_a(wd, jt) : NULL, *b = jt ? joint_body_b(wd, jt) : NULL;
    return *a && *b && (*a)->sb.body && (*b)->sb.body;
}

/* Joined bodies solve and sleep together: a node's joint partners are nodes too, along whole chains. */
static void add_joint_nodes(world *wd)
{
    island_set *is = &wd->islands;
    for (bool added = true; added;) {
        added = false;
        for (int32_t i = 0; i < wd->joints.ids.capacity; i++) {
            const body *a, *b;
            if (!joint_movers(wd, wd->joints.items[i], &a, &b))
                continue;
            const bool na = is->node_mark[a->index] == is->node_pass, nb = is->node_mark[b->index] == is->node_pass;
            if (na != nb) {
                add_node(wd, na ? b : a);
                added = true;
            }
        }
    }
}

/* The substep's nodes into wd->islands.nodes, in slot order for the awake set's part. */
static pp_status collect_nodes(world *wd)
{
    island_set *is = &wd->islands;
    if (wd->body_ids.capacity > is->node_mark_capacity) {
        const int32_t old = is->node_mark_capacity;
        pp_status st = world_slot_array(wd, (void **)&is->node_mark, &is->node_mark_capacity, sizeof *is->node_mark,
                                        "the islands");
        if (st)
            return st;
        for (int32_t i = old; i < is->node_mark_capacity; i++)
            is->node_mark[i] = 0;
    }
    pp_status st = world_slot_array(wd, (void **)&is->nodes, &is->node_capacity, sizeof *is->nodes, "the islands");
    if (st)
        return st;
    if (++is->node_pass == 0) { /* wrapped: no mark may look current */
        for (int32_t i = 0; i < is->node_mark_capacity; i++)
            is->node_mark[i] = 0;
        is->node_pass = 1;
    }
    is->node_count = 0;
    for (int32_t k = 0; k < wd->awake.count; k++)
        add_node(wd, wd->bodies[wd->awake.slots[k]]);
    is->awake_nodes = is->node_count;
    for (int32_t n = 0; n < wd->table.run_count; n++) {
        add_node(wd, wd->bodies[wd->table.runs[n].a]);
        add_node(wd, wd->bodies[wd->table.runs[n].b]);
    }
    if (wd->joints.ids.live > 0)
        add_joint_nodes(wd);
    return PP_OK;
}

/* Join a's and b's islands (either may have no ODE body) and count the rows joining them costs. */
static void join_island(int32_t *parent, int32_t *rows, int32_t *dynamic, const body *a, const body *b, int32_t n)
{
    int32_t ra = a && a->sb.body ? world_group_root(parent, (int32_t)a->index) : -1;
    int32_t rb = b && b->sb.body ? world_group_root(parent, (int32_t)b->index) : -1;
    if (ra >= 0 && rb >= 0 && ra != rb) {
        parent[ra] = rb;
        rows[rb] += rows[ra];
        dynamic[rb] += dynamic[ra];
    }
    if (ra >= 0 || rb >= 0)
        rows[rb >= 0 ? rb : ra] += n;
}

/* Each node's span. At the first substep of a pair a QuickStep stack without joints sits out; at the second
 * one whose awake bodies all sat out solves twice the time step. A lone body, cheap to solve, keeps every
 * substep's accuracy (a free fall, a rolling disc, a bounce). An island that bodies at both times joined
 * (rare: a merge in between) solves one substep, and its late bodies stay one substep late. */
static void set_spans(world *wd, int32_t k, substep_pairing pairing)
{
    const int32_t *root = wd->islands.root;
    int32_t *flags = wd->islands.group + 2 * wd->islands.group_capacity;
    /* At a step's first substep the pairs that will strike are not yet collided: nothing is at rest then. From the
     * second on, a still substep's too (it looked for no pairs, but the substeps before it did). */
    const bool at_rest_known = k > 0;
    for (int32_t n = 0; n < wd->islands.node_count; n++)
        flags[wd->islands.nodes[n]] = 0;
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        const body *bd = wd->bodies[wd->islands.nodes[n]];
        int32_t *f = &flags[root[wd->islands.nodes[n]]];
        const uint8_t every = wd->islands.every[root[wd->islands.nodes[n]]];
        *f |= (every & EVERY_SUBSTEP ? ROOT_EVERY_SUBSTEP : 0) | (every & EVERY_SLANT ? ROOT_SLANT : 0);
        if (awake_mover(bd)) {
            const bool behind = bd->sat_out + 1 == wd->islands.substep_serial;
            *f |= behind ? ROOT_BEHIND : ROOT_CURRENT;
            *f |= behind && bd->behind < 3 ? ROOT_SHORT : 0;
        }
        if (pairing == PAIR_MID || pairing == PAIR_LAST)
            *f |= carry_struck(&wd->carry, bd->index) ? ROOT_HIT : 0;
        if (bd->type == PP_BODY_KINEMATIC)
            *f |= ROOT_EVERY_SUBSTEP;
        if (at_rest_known && (carry_struck(&wd->carry, bd->index) || carry_restless(&wd->carry, bd->index)))
            *f |= ROOT_STRUCK;
        if (wd->islands.kind[bd->index] == ISLAND_EXACT_ALONE) {
            /* Its island's rows, but a fixed rotation's, are its contacts' (a joint's island is not alone). */
            const int32_t rows = wd->islands.group[wd->islands.group_capacity + root[bd->index]];
            *f |= (rows & INT32_MAX) > (bd->fixed_rotation ? ROWS_PER_FIXED_ROTATION : 0) ? ROOT_TOUCHING : 0;
            *f |= carry_was_collided(&wd->carry, bd->index) ? ROOT_COLLIDED : 0;
        }
    }
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        const int32_t i = wd->islands.nodes[n], f = flags[root[i]];
        uint8_t span = SPAN_ONE;
        /* A lone body solved exactly pairs its substeps while it rests: it has contacts, every one carried or held
         * (it moves under CARRY_MOTION_PX a step against what it touches), none collided this step. A free fall,
         * a bounce, a landing and a roll (a round body's pairs are collided) keep every substep. Whether it sat
         * the first of a pair out is what the second asks. */
        const int kind = wd->islands.kind[i];
        const bool at_rest = (f & (ROOT_TOUCHING | ROOT_COLLIDED)) == ROOT_TOUCHING;
        const bool second = pairing == PAIR_SECOND || pairing == PAIR_MID || pairing == PAIR_LAST;
        if (kind == ISLAND_QUICK_STACK || (kind == ISLAND_EXACT_ALONE && (at_rest || second))) {
            if (pairing == PAIR_FIRST && !(f & ROOT_EVERY_SUBSTEP))
                span = SPAN_SKIP;
            else if (second && (f & ROOT_SPAN_FLAGS) == ROOT_BEHIND) {
                /* A lone exact body at rest and a QuickStep stack at rest (ROOT_STRUCK clear), struck by no
                 * collided pair this step, sit the first pair of four out too and solve the four at once; list_of
                 * reads ROOT_STRUCK from the flags left behind. A stack with a slanted face stays at 2·h: at 4·h,
                 * Box2D v3's arch fell at 11 s (bench_stability). */
                if (pairing == PAIR_MID && !(f & ROOT_HIT) &&
                    ((kind == ISLAND_EXACT_ALONE && at_rest) ||
                     (kind == ISLAND_QUICK_STACK && !(f & (ROOT_STRUCK | ROOT_SLANT)))))
                    span = SPAN_SKIP;
                else
                    span = pairing == PAIR_LAST && !(f & ROOT_SHORT) ? SPAN_FOUR : SPAN_TWO;
            }
        }
        wd->islands.span[i] = span;
        if (span == SPAN_SKIP) {
            body *bd = wd->bodies[i];
            bd->behind = bd->sat_out + 1 == wd->islands.substep_serial && bd->behind < UINT8_MAX ? bd->behind + 1 : 1;
            bd->sat_out = wd->islands.substep_serial;
        }
    }
}

/* Which of solver_step's lists (SOLVE_*) a node goes in, or -1: asleep, or a QuickStep island's sleeper (ODE
 * wakes it through its contact). A stack over 2·h that no collided pair touched this step, and whose pairs move
 * slower than CARRY_REST_PX, is at rest (set_spans's ROOT_STRUCK, left in the group array's last third). A stack
 * over 4·h keeps every iteration: at half, the 20-row pyramid drifted 3.4 px in bench_stability, not 0.6. A lone
 * body at rest keeps every iteration: at half, a 1 px grain slid 0.012 px as it settled (test_extremes) and
 * ramp20's slide moved 0.5 %, for 8 % of the destruction scene's step. */
static int list_of(world *wd, int32_t i)
{
    const body *bd = wd->bodies[i];
    const int32_t root = wd->islands.root[i];
    if (wd->islands.group[wd->islands.group_capacity + root] >= 0)
        return -1; /* the island's rows carry no awake mark: asleep */
    if (island_exact(wd->islands.kind[i]))
        switch (wd->islands.span[i]) {
        case SPAN_FOUR: return SOLVE_EXACT_FOUR;
        case SPAN_TWO: return SOLVE_EXACT_TWO;
        case SPAN_ONE: return SOLVE_EXACT;
        default: return SOLVE_IDLE;
        }
    if (!awake_mover(bd))
        return -1;
    const int32_t f = wd->islands.group[2 * wd->islands.group_capacity + root];
    const bool struck = (f & ROOT_STRUCK) != 0;
    switch (wd->islands.span[i]) {
    case SPAN_FOUR: return SOLVE_QUICK_FOUR;
    case SPAN_TWO: return struck ? SOLVE_QUICK_TWO : SOLVE_QUICK_TWO_REST;
    case SPAN_ONE: return SOLVE_QUICK;
    default: return SOLVE_IDLE;
    }
}

/* The stepped islands' bodies for solver_step, one list after another in wd->islands.bodies, each in node
 * order (solver_ode.h: SOLVE_*). */
static void list_islands(world *wd, solver_islands *out)
{
    int32_t filled[SOLVE_LISTS] = {0};
    int8_t *list = wd->islands.list;
    *out = (solver_islands){{0}, {0}};
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        list[n] = (int8_t)list_of(wd, wd->islands.nodes[n]);
        if (list[n] >= 0)
            out->count[list[n]]++;
    }
    out->list[0] = wd->islands.bodies;
    for (int w = 1; w < SOLVE_LISTS; w++)
        out->list[w] = out->list[w - 1] + out->count[w - 1];
    for (int32_t n = 0; n < wd->islands.node_count; n++)
        if (list[n] >= 0)
            out->list[list[n]][filled[list[n]]++] = &wd->bodies[wd->islands.nodes[n]]->sb;
}

/* What the islands are made of: the contacts' pairs and the awake set, as a digest (PP_CHECKS builds). */
static uint64_t plan_digest(const world *wd)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (int32_t k = 0; k < wd->contact_count; k = contact_pair_end(wd, k))
        h = (h ^ wd->contacts[k].a.id ^ (wd->contacts[k].b.id << 1)) * 0x100000001b3ull;
    for (int32_t k = 0; k < wd->awake.count; k++)
        h = (h ^ (uint64_t)wd->awake.slots[k] ^ (uint64_t)awake_mover(wd->bodies[wd->awake.slots[k]]) << 40) *
            0x100000001b3ull;
    return h;
}

/* A still substep's islands are made from what the last plan saw. */
static void island_validate_still(const world *wd)
{
#ifdef PP_CHECKS
    PP_ASSERT(plan_digest(wd) == wd->islands.planned);
#else
    (void)wd;
    (void)plan_digest;
#endif
}

pp_status island_plan(world *wd, int32_t k, substep_pairing pairing, bool still, solver_islands *out)
{
    wd->islands.substep_serial++;
    *out = (solver_islands){{0}, {0}};
    contact_table_validate_runs(wd);
    if (still && wd->islands.node_count > 0) { /* the same nodes, islands and kinds: only the spans move on */
        island_validate_still(wd);
        set_spans(wd, k, pairing);
        list_islands(wd, out);
        return PP_OK;
    }
    wd->islands.node_count = wd->islands.awake_nodes = 0;
    /* Nodes come from the awake set and the contacts (joints only extend them): with neither, none. */
    if (wd->body_ids.capacity == 0 || (wd->awake.count == 0 && wd->contact_count == 0))
        return PP_OK;
    island_set *isl = &wd->islands;
    static const char *what = "the islands";
    pp_status st = world_slot_array(wd, (void **)&isl->group, &isl->group_capacity, 3 * sizeof *isl->group, what);
    if (st || (st = world_slot_array(wd, (void **)&isl->root, &isl->root_capacity, sizeof *isl->root, what)) || (st = world_slot_array(wd, (void **)&isl->bodies, &isl->bodies_capacity, sizeof *isl->bodies, what)) ||
        (st = world_slot_array(wd, (void **)&isl->kind, &isl->kind_capacity, 1, what)) ||
        (st = world_slot_array(wd, (void **)&isl->span, &isl->span_capacity, 1, what)) ||
        (st = world_slot_array(wd, (void **)&isl->list, &isl->list_capacity, 1, what)) ||
        (st = world_slot_array(wd, (void **)&isl->heaviest, &isl->heaviest_capacity, sizeof *isl->heaviest, what)) ||
        (st = world_slot_array(wd, (void **)&isl->every, &isl->every_capacity, 1, what)) ||
        (st = world_slot_array(wd, (void **)&isl->sleep_group, &isl->sleep_group_capacity, 2 * sizeof *isl->sleep_group,
                               what)) ||
        (st = collect_nodes(wd)))
        return st;
    /* Per root: the island's rows (the group array's second third), why it may not be solved exactly (NOT_EXACT_*
     * bits in the last third, until set_spans takes it) and its dynamic bodies. */
    int32_t *parent = wd->islands.group, *rows = wd->islands.group + wd->islands.group_capacity;
    int32_t *not_exact = wd->islands.group + 2 * wd->islands.group_capacity;
    int32_t *dynamic = (int32_t *)wd->islands.bodies; /* scratch until the lists are written */
    PP_ASSERT(sizeof *wd->islands.bodies >= sizeof *dynamic);
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        const int32_t i = wd->islands.nodes[n];
        const body *bd = wd->bodies[i];
        parent[i] = i;
        rows[i] = bd->fixed_rotation ? ROWS_PER_FIXED_ROTATION : 0;
        not_exact[i] = 0;
        wd->islands.heaviest[i] = 0;
        dynamic[i] = bd->type == PP_BODY_DYNAMIC;
    }
    for (int32_t n = 0; n < wd->table.run_count; n++) {
        const contact_run *u = &wd->table.runs[n];
        join_island(parent, rows, dynamic, wd->bodies[u->a], wd->bodies[u->b], ROWS_PER_CONTACT * (u->end - u->first));
    }
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        const body *a = jt ? joint_body_a(wd, jt) : NULL, *b = jt ? joint_body_b(wd, jt) : NULL;
        if (is_node(wd, a) || is_node(wd, b)) {
            join_island(parent, rows, dynamic, a, b, ROWS_PER_JOINT);
            const body *node = is_node(wd, a) ? a : b;
            not_exact[world_group_root(parent, (int32_t)node->index)] |= NOT_EXACT_ALONE;
        }
    }
    /* The islands are whole: each node's root, found once here, is what every later pass (set_spans and list_of
     * at this substep and the still ones after it) reads. */
    /* What has an island solve every substep, for this plan and the still ones after it: a joint, or a body pressing
     * on one over HARD_MASS_RATIO times lighter. */
    int32_t *root_of = isl->root;
    uint8_t *every = isl->every;
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        const int32_t i = wd->islands.nodes[n];
        root_of[i] = world_group_root(parent, i);
        every[i] = 0;
    }
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        const body *a = jt ? joint_body_a(wd, jt) : NULL, *b = jt ? joint_body_b(wd, jt) : NULL;
        const body *node = is_node(wd, a) ? a : is_node(wd, b) ? b : NULL;
        if (node)
            every[root_of[node->index]] |= EVERY_SUBSTEP;
    }
    /* After every join: a flag put on a root that a later joint puts under another would be lost. */
    for (int32_t n = 0; n < wd->table.run_count; n++) {
        const contact_run *u = &wd->table.runs[n];
        const body *a = wd->bodies[u->a], *b = wd->bodies[u->b];
        if (a->type == PP_BODY_DYNAMIC && b->type == PP_BODY_DYNAMIC &&
            dmax(a->mass.mass, b->mass.mass) > HARD_MASS_RATIO * dmin(a->mass.mass, b->mass.mass))
            every[root_of[a->index]] |= EVERY_SUBSTEP;
        if (island_slanted_face(wd, u->first, u->end)) {
            not_exact[root_of[u->node]] |= NOT_EXACT_SLANT;
            every[root_of[u->node]] |= EVERY_SLANT;
        }
    }
    /* An island with a body whose ODE centre of mass is far outside its bitmap (a snapshot can hold one,
     * fuzz_snapshot: 9e17 m) stays on QuickStep: the exact solver's lever arms would end in NaN and ODE's
     * abort in dNormalize4, where QuickStep's non-finite result is caught and the step undone. */
    /* An island is stepped if any of its bodies is awake (ODE wakes the rest): its rows carry the mark. */
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        const body *bd = wd->bodies[wd->islands.nodes[n]];
        const int32_t root = root_of[wd->islands.nodes[n]];
        if (!within_reach(wd, bd)) {
            dynamic[root] = INT32_MIN / 2; /* solved as a lone body: every substep */
            not_exact[root] |= NOT_EXACT;
        }
        double *heaviest = &wd->islands.heaviest[root];
        if (bd->type == PP_BODY_DYNAMIC && bd->mass.mass > *heaviest)
            *heaviest = bd->mass.mass;
        if (awake_mover(bd))
            rows[root] |= INT32_MIN;
    }
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        const int32_t i = wd->islands.nodes[n], root = root_of[i];
        const body *bd = wd->bodies[i];
        if (bd->type == PP_BODY_DYNAMIC && wd->islands.heaviest[root] > EXACT_MASS_RATIO * bd->mass.mass)
            not_exact[root] |= NOT_EXACT;
        wd->islands.kind[i] = dynamic[root] < 2 ? ISLAND_QUICK_ALONE : ISLAND_QUICK_STACK;
        if (dynamic[root] != 1 || bd->raster.width < 2 || bd->raster.height < 2)
            not_exact[root] |= NOT_EXACT_ALONE;
    }
    const int32_t limit = wd->def.exact_island_rows;
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        const int32_t i = wd->islands.nodes[n], root = root_of[i], r = rows[root];
        const bool alone = wd->islands.kind[i] == ISLAND_QUICK_ALONE;
        if (r < 0 && !(not_exact[root] & NOT_EXACT) &&
            (wd->def.exact_solver || ((r & INT32_MAX) <= limit && !(alone && (not_exact[root] & NOT_EXACT_ALONE)) &&
                                      (alone || !(not_exact[root] & NOT_EXACT_SLANT)))))
            wd->islands.kind[i] = alone ? ISLAND_EXACT_ALONE : ISLAND_EXACT;
    }
#ifdef PP_CHECKS
    wd->islands.planned = plan_digest(wd);
#endif
    set_spans(wd, k, pairing);
    list_islands(wd, out);
    return PP_OK;
}

void island_list_woken(world *wd)
{
    /* The awake set's own nodes are in it already. */
    for (int32_t n = wd->islands.awake_nodes; n < wd->islands.node_count; n++) {
        body *bd = wd->bodies[wd->islands.nodes[n]];
        if (awake_mover(bd))
            awake_add(wd, bd);
    }
}

bool island_sleep(world *wd, double h)
{
    const pp_world_def *d = &wd->def;
    if (!d->allow_sleep) /* nothing sleeps: island_sleep_off sets the timers once a step */
        return false;
    bool ready = false; /* an awake body slow for sleep_time: only such a body can fall asleep */
    for (int32_t k = 0; k < wd->awake.count; k++) {
        body *bd = wd->bodies[wd->awake.slots[k]];
        if (bd->type != PP_BODY_DYNAMIC || !awake_mover(bd))
            continue;
        if (bd->slow_time > d->sleep_time)
            bd->slow_time = 0; /* woken since it slept (the mark set below) */
        dvec2 v;
        double w;
        solver_body_get_velocity(wd->solver, &bd->sb, &v, &w);
        const double vmax = d->sleep_linear_speed; /* squared: no hypot for every body every substep */
        const bool slow = dv_dot(v, v) <= vmax * vmax && fabs(w) <= d->sleep_angular_speed;
        /* Capped at sleep_time while awake: ready, waiting for the rest of its group. */
        bd->slow_time = slow ? dmin(bd->slow_time + h, d->sleep_time) : 0;
        ready |= bd->slow_time >= d->sleep_time;
    }
    if (!ready || wd->islands.node_count == 0)
        return false; /* no node: nothing awake, and maybe no arrays yet */
    /* Sleep groups: dynamic bodies joined by contacts, over the nodes island_plan collected (every body of a
     * group with an awake body is one: awake, or a contact's). */
    int32_t *parent = wd->islands.sleep_group, *restless = wd->islands.sleep_group + wd->islands.sleep_group_capacity;
    for (int32_t n = 0; n < wd->islands.node_count; n++)
        parent[wd->islands.nodes[n]] = wd->islands.nodes[n], restless[wd->islands.nodes[n]] = 0;
    for (int32_t n = 0; n < wd->table.run_count; n++) {
        const body *a = wd->bodies[wd->table.runs[n].a], *b = wd->bodies[wd->table.runs[n].b];
        if (a->type == PP_BODY_DYNAMIC && b->type == PP_BODY_DYNAMIC)
            parent[world_group_root(parent, (int32_t)a->index)] = world_group_root(parent, (int32_t)b->index);
    }
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        const body *a, *b;
        if (joint_movers(wd, wd->joints.items[i], &a, &b) && a->type == PP_BODY_DYNAMIC && b->type == PP_BODY_DYNAMIC &&
            wd->islands.node_mark[a->index] == wd->islands.node_pass)
            parent[world_group_root(parent, (int32_t)a->index)] = world_group_root(parent, (int32_t)b->index);
    }
    bool slept = false;
    /* A group with a body not yet ready stays awake. */
    for (int32_t n = 0; n < wd->islands.node_count; n++) {
        const body *bd = wd->bodies[wd->islands.nodes[n]];
        if (bd->type == PP_BODY_DYNAMIC && bd->slow_time < d->sleep_time)
            restless[world_group_root(parent, wd->islands.nodes[n])] = 1;
    }
    for (int32_t k = 0; k < wd->awake.count; k++) {
        body *bd = wd->bodies[wd->awake.slots[k]];
        if (bd->type == PP_BODY_DYNAMIC && awake_mover(bd) && !restless[world_group_root(parent, (int32_t)bd->index)]) {
            solver_body_sleep(&bd->sb);
            awake_slept(wd, bd);
            bd->slow_time = d->sleep_time + 1; /* asleep: past sleep_time marks it */
            slept = true;
        }
    }
    return slept;
}

void island_sleep_off(world *wd)
{
    PP_ASSERT(!wd->def.allow_sleep);
    for (int32_t k = 0; k < wd->awake.count; k++) {
        body *bd = wd->bodies[wd->awake.slots[k]];
        if (bd->type == PP_BODY_DYNAMIC && awake_mover(bd))
            bd->slow_time = 0;
    }
}

void island_free(island_set *is)
{
    pp_free(is->group);
    pp_free(is->root);
    pp_free(is->node_mark);
    pp_free(is->nodes);
    pp_free(is->bodies);
    pp_free(is->kind);
    pp_free(is->span);
    pp_free(is->list);
    pp_free(is->heaviest);
    pp_free(is->every);
    pp_free(is->sleep_group);
    *is = (island_set){0};
}
