/* Contacts into solver rows: each contact's bounce, its closing and friction-anchor target speeds, and the
 * order its joints are handed to ODE in. */
#include "contact_solve.h"
#include "corner.h"
#include "world.h"

#include <math.h>

static double inv_mass(const body *bd)
{
    return bd->type == PP_BODY_DYNAMIC && bd->mass.mass > 0 ? 1.0 / bd->mass.mass : 0.0;
}

/* The tangential speed that takes back, at the contact_erp rate, what a contact has slipped since its
 * pair's friction anchor t (contact_table.c); Coulomb's bound still caps the force, so a sliding body slides.
 * Stacks slip unasked: QuickStep's because its solve stops short, the exact solver's because contact_cfm
 * lets a contact under a steady sideways load give (a 3-level card house's tents walked 0.035 px/s and
 * fell at 19 s; an arch crept 3 px). A lone body is left free (pair_solve finds it no anchor): its anchor
 * would brake a roll. */
static double anchor_speed(const world *wd, const body *a, const body *b, const contact_record *t,
                           const pp_contact *c, double h)
{
    const dvec2 slip = contact_anchor_slip(t, a, b, dv(c->point.x, c->point.y));
    const double along = dv_dot(slip, dv(-c->normal.y, c->normal.x));
    const double v = wd->def.contact_erp * along / h, cap = wd->def.max_correction_speed;
    return dmax(-cap, dmin(cap, v));
}

/* How fast the pair's points meet along the contact normal, px/s (> 0: approaching). */
static double approach_speed(const world *wd, const body *a, const body *b, const pp_contact *c)
{
    const dvec2 p = dv(c->point.x, c->point.y), n = dv(c->normal.x, c->normal.y);
    return -dv_dot(dv_sub(body_point_velocity(wd, b, p), body_point_velocity(wd, a, p)), n);
}

/* The contact is found a substep late, up to a substep's travel deep, and a bounce of e·v from there
 * would rise e²·depth short. The coefficient handed to ODE instead gives the speed that, against the
 * pair's gravity along the normal, reaches the slop depth at e times the speed the bodies met with:
 * v_out² = e²·v² + 2·g·d·(1 − e²), d the depth past contact_slop. Never more than the approach speed.
 * `closing` is the point's approach_speed; ODE bounces nothing slower than bounce_threshold. */
static double bounce_for(const world *wd, const body *a, const body *b, const pp_contact *c, double e, double closing)
{
    if (!(closing > wd->def.bounce_threshold))
        return e; /* ODE bounces nothing this slow */
    const dvec2 n = dv(c->normal.x, c->normal.y);
    const dvec2 g = dv(wd->def.gravity.x, wd->def.gravity.y);
    const dvec2 ga = a->type == PP_BODY_DYNAMIC ? g : dv(0, 0), gb = b->type == PP_BODY_DYNAMIC ? g : dv(0, 0);
    const double g_closing = -dv_dot(dv_sub(gb, ga), n), d = dmax(0.0, c->depth - wd->def.contact_slop);
    const double v2 = e * e * closing * closing + 2.0 * dmax(0.0, g_closing) * d * (1.0 - e * e);
    return dmin(dmax(e, sqrt(v2) / closing), dmax(e, 1.0));
}

/* ODE's surface layer leaves a contact shallower than contact_slop where it is, and the contact's softness
 * (contact_cfm) lets a loaded pile creep down through that band for seconds: a 20-box tower solved exactly
 * sank 1.3 px in the minute after its first second, a QuickStep pyramid 0.65 px. Instead the pair closes
 * that gap at the contact_erp rate, as the depth past it is pushed out, so a pile settles in a few steps.
 * On an exact island the whole pair closes by its deepest point's gap: closing each point by its own let a
 * tilted pair rock freely up to that speed, and an arch's feet walked apart (it fell at 4 s). Not where
 * QuickStep's weak solve meets a light body carrying one over 4 times its mass (a 1:10:100:1000 chain fell
 * through the gap), not on a lone body (nothing loads it but its own weight), not on a bounce (it keeps
 * its own speed), and not where a corner meets a face (CORNER_PIXELS) along a normal over 45° off gravity:
 * that corner bears no weight to creep with, and the only way to close its gap may be to slide along the face.
 * The top tent of Box2D v3's card house stands on such a corner, a card's top on the other's face 25° off
 * level; closed, the card slid down that face from the first frame at 30 to 120 iterations and the house fell
 * at 0.13 s (BALANCED's 20 stood it half the time). A card's foot on a flat bears weight and keeps it. */
enum { CLOSING_MASS_RATIO = 4 };
#define COS_BEARING 0.70710678118654752 /* cos 45° */

/* What a pair's points share, found once a pair. */
typedef struct pair_solve {
    const body *a, *b;
    const contact_record *anchor; /* its friction anchor, on a stack's island (anchor_speed); else NULL */
    double h;                     /* the time step of its island, s */
    double inv_mass_a, inv_mass_b, friction, restitution;
    double deepest;               /* px, its deepest point's depth */
    bool closes;                  /* its island closes the slop band (see above) */
    bool exact;                   /* on an exact island: the pair closes by its deepest point */
} pair_solve;

static pair_solve pair_solve_of(const world *wd, const contact_run *u, int span, double h)
{
    pair_solve p = {.a = wd->bodies[u->a], .b = wd->bodies[u->b], .h = span * h};
    const int kind = wd->islands.kind[u->node];
    const bool stack = kind == ISLAND_QUICK_STACK || kind == ISLAND_EXACT;
    p.inv_mass_a = inv_mass(p.a), p.inv_mass_b = inv_mass(p.b);
    p.friction = sqrt(p.a->friction * p.b->friction);
    p.restitution = dmax(p.a->restitution, p.b->restitution);
    const double ia = p.inv_mass_a, ib = p.inv_mass_b;
    p.closes = stack && !(kind == ISLAND_QUICK_STACK && ia > 0 && ib > 0 &&
                          dmax(ia, ib) > CLOSING_MASS_RATIO * dmin(ia, ib));
    p.exact = kind == ISLAND_EXACT;
    p.deepest = wd->contacts[u->first].depth;
    for (int32_t j = u->first + 1; j < u->end; j++)
        p.deepest = dmax(p.deepest, wd->contacts[j].depth);
    p.anchor = stack ? &wd->table.records[u->record] : NULL; /* a is the record's a: the lower slot */
    return p;
}

/* The speed at which c's pair closes the slop band's gap at c (0: not at all). `g` is gravity's length,
 * `bounce` whether c bounces this substep. */
static double closing_speed(const world *wd, const pair_solve *p, const pp_contact *c, double g, bool bounce)
{
    const double gap = wd->def.contact_slop - (p->exact ? p->deepest : c->depth);
    if (!p->closes || !(gap > 0) || bounce)
        return 0;
    /* A corner bears weight when its normal lies within 45° of gravity. */
    const bool bears_weight = g > 0 && fabs(c->normal.x * wd->def.gravity.x + c->normal.y * wd->def.gravity.y) >=
                                           COS_BEARING * g;
    if (c->pixel_count <= CORNER_PIXELS && !bears_weight)
        return 0;
    return wd->def.contact_erp * gap / p->h;
}

void contact_joints_add(world *wd, double h)
{
    const double g = hypot(wd->def.gravity.x, wd->def.gravity.y);
    for (int32_t n = 0; n < wd->table.run_count; n++) {
        const contact_run *u = &wd->table.runs[n];
        const int span = contact_run_span(wd, u);
        if (span == SPAN_SKIP)
            continue;
        const pair_solve p = pair_solve_of(wd, u, span, h);
        const solver_body *sa = p.a->sb.body ? &p.a->sb : NULL, *sb = p.b->sb.body ? &p.b->sb : NULL;
        for (int32_t i = u->first; i < u->end; i++) {
            const pp_contact *c = &wd->contacts[i];
            const double e = p.restitution, closing = e > 0 ? approach_speed(wd, p.a, p.b, c) : 0;
            const bool bounce = e > 0 && closing > wd->def.bounce_threshold;
            *solver_add_contact(wd->solver, i) = (solver_contact){
                sa, sb, p.inv_mass_a, p.inv_mass_b,
                dv(c->point.x, c->point.y), dv(c->normal.x, c->normal.y), c->depth,
                p.friction, e > 0 ? bounce_for(wd, p.a, p.b, c, e, closing) : 0,
                p.anchor ? anchor_speed(wd, p.a, p.b, p.anchor, c, p.h) : 0, closing_speed(wd, &p, c, g, bounce),
                (uint8_t)span, bounce,
            };
        }
    }
}
