/* Islands: which bodies solve together and which sleep together. ODE steps one method per world, so the
 * islands are chosen here and solver_step hides the others while each method runs. An island is what ODE's
 * own walk will find: bodies with ODE bodies (dynamic or kinematic) joined by contacts; static bodies join
 * nothing. The exact solver takes an island of two or more dynamic bodies (where QuickStep's unfinished
 * solve lets stacks sag, creep and crush light bodies) up to exact_island_rows; a lone body is QuickStep's
 * either way, as it always was.
 * Both passes visit only the substep's nodes: the awake set's movable bodies and the contacts' movable
 * bodies (a sleeper touched by an awake body). A sleeping island is never visited. */
#include "island.h"
#include "awake.h"
#include "joint.h"

/* Constraint rows a contact costs (the normal and one in-plane friction row), and at most a joint's. */
enum { ROWS_PER_CONTACT = 2, ROWS_PER_FIXED_ROTATION = 4, ROWS_PER_JOINT = 6 };

/* What an island holds, for its span: a joint (whose springs are tuned to one substep) or a body pressing on
 * one over HARD_MASS_RATIO times lighter (QuickStep at twice the time step let a 1:10:100:1000 chain fall),
 * both solved every substep; an awake body that sat the last substep out, and one that did not. */
enum { ROOT_EVERY_SUBSTEP = 1, ROOT_BEHIND = 2, ROOT_CURRENT = 4 };
enum { HARD_MASS_RATIO = 4 };

static bool within_reach(const world *wd, const body *bd)
{
    const double reach = 1.0 + (double)bd->raster.width + (double)bd->raster.height;
    const dvec2 off = dv_sub(solver_body_get_com(wd->solver, &bd->sb), body_com_world(bd));
    return dv_dot(off, off) <= reach * reach;
}

static bool is_node(const world *wd, const body *bd)
{
    return bd && bd->sb.body && wd->node_mark[bd->index] == wd->node_pass;
}

/* Make a movable body a node of this pass (once): its own root, value 0. */
static void add_node(world *wd, const body *bd)
{
    const int32_t i = (int32_t)bd->index;
    if (!bd->sb.body || wd->node_mark[i] == wd->node_pass)
        return;
    wd->node_mark[i] = wd->node_pass;
    wd->nodes[wd->node_count++] = i;
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
    for (bool added = true; added;) {
        added = false;
        for (int32_t i = 0; i < wd->joints.ids.capacity; i++) {
            const body *a, *b;
            if (!joint_movers(wd, wd->joints.items[i], &a, &b))
                continue;
            const bool na = wd->node_mark[a->index] == wd->node_pass, nb = wd->node_mark[b->index] == wd->node_pass;
            if (na != nb) {
                add_node(wd, na ? b : a);
                added = true;
            }
        }
    }
}

/* The substep's nodes into wd->nodes, in slot order for the awake set's part. */
static pp_status collect_nodes(world *wd)
{
    if (wd->body_ids.capacity > wd->node_mark_capacity) {
        const int32_t old = wd->node_mark_capacity;
        pp_status st = world_slot_array(wd, (void **)&wd->node_mark, &wd->node_mark_capacity, sizeof *wd->node_mark,
                                        "the islands");
        if (st)
            return st;
        for (int32_t i = old; i < wd->node_mark_capacity; i++)
            wd->node_mark[i] = 0;
    }
    pp_status st = world_slot_array(wd, (void **)&wd->nodes, &wd->node_capacity, sizeof *wd->nodes, "the islands");
    if (st)
        return st;
    if (++wd->node_pass == 0) { /* wrapped: no mark may look current */
        for (int32_t i = 0; i < wd->node_mark_capacity; i++)
            wd->node_mark[i] = 0;
        wd->node_pass = 1;
    }
    wd->node_count = 0;
    for (int32_t k = 0; k < wd->awake_count; k++)
        add_node(wd, wd->bodies[wd->awake_slots[k]]);
    for (int32_t k = 0; k < wd->contact_count; k++) {
        add_node(wd, body_of(wd, wd->contacts[k].a));
        add_node(wd, body_of(wd, wd->contacts[k].b));
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
static void set_spans(world *wd, substep_pairing pairing)
{
    int32_t *parent = wd->group, *flags = wd->group + 2 * wd->group_capacity;
    for (int32_t n = 0; n < wd->node_count; n++)
        flags[wd->nodes[n]] = 0;
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        const body *a = jt ? joint_body_a(wd, jt) : NULL, *b = jt ? joint_body_b(wd, jt) : NULL;
        const body *node = is_node(wd, a) ? a : is_node(wd, b) ? b : NULL;
        if (node)
            flags[world_group_root(parent, (int32_t)node->index)] |= ROOT_EVERY_SUBSTEP;
    }
    for (int32_t k = 0; k < wd->contact_count; k++) {
        const body *a = body_of(wd, wd->contacts[k].a), *b = body_of(wd, wd->contacts[k].b);
        if (a->type == PP_BODY_DYNAMIC && b->type == PP_BODY_DYNAMIC &&
            fmax(a->mass.mass, b->mass.mass) > HARD_MASS_RATIO * fmin(a->mass.mass, b->mass.mass))
            flags[world_group_root(parent, (int32_t)a->index)] |= ROOT_EVERY_SUBSTEP;
    }
    for (int32_t n = 0; n < wd->node_count; n++) {
        const body *bd = wd->bodies[wd->nodes[n]];
        if (awake_mover(bd))
            flags[world_group_root(parent, wd->nodes[n])] |=
                bd->sat_out + 1 == wd->substep_serial ? ROOT_BEHIND : ROOT_CURRENT;
    }
    for (int32_t n = 0; n < wd->node_count; n++) {
        const int32_t i = wd->nodes[n], f = flags[world_group_root(parent, i)];
        uint8_t span = SPAN_ONE;
        if (wd->island_kind[i] == ISLAND_QUICK_STACK) {
            if (pairing == PAIR_FIRST && !(f & ROOT_EVERY_SUBSTEP))
                span = SPAN_SKIP;
            else if (pairing == PAIR_SECOND && f == ROOT_BEHIND)
                span = SPAN_TWO;
        }
        wd->island_span[i] = span;
        if (span == SPAN_SKIP)
            wd->bodies[i]->sat_out = wd->substep_serial;
    }
}

/* Which of solver_step's lists a node goes in (0 exact, 1 QuickStep over h, 2 over 2·h, 3 sitting out), or
 * -1: asleep, or a QuickStep island's sleeper (ODE wakes it through its contact). */
static int list_of(world *wd, int32_t i)
{
    const body *bd = wd->bodies[i];
    if (wd->group[wd->group_capacity + world_group_root(wd->group, i)] >= 0)
        return -1; /* the island's rows carry no awake mark: asleep */
    if (wd->island_kind[i] == ISLAND_EXACT)
        return 0;
    if (!awake_mover(bd))
        return -1;
    return wd->island_span[i] == SPAN_ONE ? 1 : wd->island_span[i] == SPAN_TWO ? 2 : 3;
}

/* The stepped islands' bodies for solver_step, one list after another in wd->island_bodies, each in node
 * order: every body of the exact islands (ODE wakes their sleepers), then QuickStep's awake bodies over h,
 * over 2·h, and those sitting out. */
static void list_islands(world *wd, solver_islands *out)
{
    int32_t counts[4] = {0}, filled[4] = {0};
    for (int32_t n = 0; n < wd->node_count; n++) {
        const int which = list_of(wd, wd->nodes[n]);
        if (which >= 0)
            counts[which]++;
    }
    solver_body **start[4] = {wd->island_bodies};
    for (int w = 1; w < 4; w++)
        start[w] = start[w - 1] + counts[w - 1];
    for (int32_t n = 0; n < wd->node_count; n++) {
        const int which = list_of(wd, wd->nodes[n]);
        if (which >= 0)
            start[which][filled[which]++] = &wd->bodies[wd->nodes[n]]->sb;
    }
    *out = (solver_islands){start[0], counts[0], start[1], counts[1], start[2], counts[2], start[3], counts[3]};
}

pp_status island_plan(world *wd, substep_pairing pairing, solver_islands *out)
{
    wd->substep_serial++;
    *out = (solver_islands){0};
    wd->node_count = 0;
    if (wd->body_ids.capacity == 0)
        return PP_OK;
    pp_status st = world_slot_array(wd, (void **)&wd->group, &wd->group_capacity, 3 * sizeof *wd->group,
                                    "the islands");
    if (st || (st = world_slot_array(wd, (void **)&wd->island_bodies, &wd->island_capacity,
                                     sizeof *wd->island_bodies, "the islands")) ||
        (st = world_slot_array(wd, (void **)&wd->island_kind, &wd->island_kind_capacity, 1, "the islands")) ||
        (st = world_slot_array(wd, (void **)&wd->island_span, &wd->island_span_capacity, 1, "the islands")) ||
        (st = collect_nodes(wd)))
        return st;
    /* Per root: the island's rows (the group array's second third) and its dynamic bodies. */
    int32_t *parent = wd->group, *rows = wd->group + wd->group_capacity;
    int32_t *dynamic = (int32_t *)wd->island_bodies; /* scratch until the lists are written */
    PP_ASSERT(sizeof *wd->island_bodies >= sizeof *dynamic);
    for (int32_t n = 0; n < wd->node_count; n++) {
        const int32_t i = wd->nodes[n];
        const body *bd = wd->bodies[i];
        parent[i] = i;
        rows[i] = bd->fixed_rotation ? ROWS_PER_FIXED_ROTATION : 0;
        dynamic[i] = bd->type == PP_BODY_DYNAMIC;
    }
    for (int32_t k = 0; k < wd->contact_count; k++)
        join_island(parent, rows, dynamic, body_of(wd, wd->contacts[k].a), body_of(wd, wd->contacts[k].b),
                    ROWS_PER_CONTACT);
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        const body *a = jt ? joint_body_a(wd, jt) : NULL, *b = jt ? joint_body_b(wd, jt) : NULL;
        if (is_node(wd, a) || is_node(wd, b))
            join_island(parent, rows, dynamic, a, b, ROWS_PER_JOINT);
    }
    /* An island with a body whose ODE centre of mass is far outside its bitmap (a snapshot can hold one,
     * fuzz_snapshot: 9e17 m) stays on QuickStep: the exact solver's lever arms would end in NaN and ODE's
     * abort in dNormalize4, where QuickStep's non-finite result is caught and the step undone. */
    for (int32_t n = 0; n < wd->node_count; n++)
        if (!within_reach(wd, wd->bodies[wd->nodes[n]]))
            dynamic[world_group_root(parent, wd->nodes[n])] = INT32_MIN / 2;
    for (int32_t n = 0; n < wd->node_count; n++) {
        const int32_t i = wd->nodes[n];
        wd->island_kind[i] = dynamic[world_group_root(parent, i)] < 2 ? ISLAND_QUICK_ALONE : ISLAND_QUICK_STACK;
    }
    /* An island is stepped if any of its bodies is awake (ODE wakes the rest); mark those roots. */
    for (int32_t n = 0; n < wd->node_count; n++)
        if (awake_mover(wd->bodies[wd->nodes[n]]))
            rows[world_group_root(parent, wd->nodes[n])] |= INT32_MIN;
    const int32_t limit = wd->def.exact_island_rows;
    for (int32_t n = 0; n < wd->node_count; n++) {
        const int32_t i = wd->nodes[n], r = rows[world_group_root(parent, i)];
        if (r < 0 && (wd->def.exact_solver || (wd->island_kind[i] == ISLAND_QUICK_STACK && (r & INT32_MAX) <= limit)))
            wd->island_kind[i] = ISLAND_EXACT;
    }
    set_spans(wd, pairing);
    list_islands(wd, out);
    return PP_OK;
}

void island_list_woken(world *wd)
{
    for (int32_t n = 0; n < wd->node_count; n++) {
        body *bd = wd->bodies[wd->nodes[n]];
        if (awake_mover(bd))
            awake_add(wd, bd);
    }
}

bool island_sleep(world *wd, double h)
{
    const pp_world_def *d = &wd->def;
    for (int32_t k = 0; k < wd->awake_count; k++) {
        body *bd = wd->bodies[wd->awake_slots[k]];
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
        bd->slow_time = slow && d->allow_sleep ? fmin(bd->slow_time + h, d->sleep_time) : 0;
    }
    if (!d->allow_sleep || wd->node_count == 0)
        return false; /* no node: nothing awake, and maybe no arrays yet */
    /* Sleep groups: dynamic bodies joined by contacts, over the nodes island_plan collected (every body of a
     * group with an awake body is one: awake, or a contact's). */
    int32_t *parent = wd->group, *restless = wd->group + wd->group_capacity;
    for (int32_t n = 0; n < wd->node_count; n++)
        parent[wd->nodes[n]] = wd->nodes[n], restless[wd->nodes[n]] = 0;
    for (int32_t k = 0; k < wd->contact_count; k++) {
        const body *a = body_of(wd, wd->contacts[k].a), *b = body_of(wd, wd->contacts[k].b);
        if (a->type == PP_BODY_DYNAMIC && b->type == PP_BODY_DYNAMIC)
            parent[world_group_root(parent, (int32_t)a->index)] = world_group_root(parent, (int32_t)b->index);
    }
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        const body *a, *b;
        if (joint_movers(wd, wd->joints.items[i], &a, &b) && a->type == PP_BODY_DYNAMIC && b->type == PP_BODY_DYNAMIC &&
            wd->node_mark[a->index] == wd->node_pass)
            parent[world_group_root(parent, (int32_t)a->index)] = world_group_root(parent, (int32_t)b->index);
    }
    bool slept = false;
    /* A group with a body not yet ready stays awake. */
    for (int32_t n = 0; n < wd->node_count; n++) {
        const body *bd = wd->bodies[wd->nodes[n]];
        if (bd->type == PP_BODY_DYNAMIC && bd->slow_time < d->sleep_time)
            restless[world_group_root(parent, wd->nodes[n])] = 1;
    }
    for (int32_t k = 0; k < wd->awake_count; k++) {
        body *bd = wd->bodies[wd->awake_slots[k]];
        if (bd->type == PP_BODY_DYNAMIC && awake_mover(bd) && !restless[world_group_root(parent, (int32_t)bd->index)]) {
            solver_body_sleep(&bd->sb);
            bd->slow_time = d->sleep_time + 1; /* asleep: past sleep_time marks it */
            slept = true;
        }
    }
    return slept;
}
