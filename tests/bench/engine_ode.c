/* The analytic baseline: the same scene with ODE's own boxes (dCreateBox in a hash space,
 * dSpaceCollide, contact joints), set up the way PhysPix sets ODE up (lib/dynamics/solver_ode.c):
 * px/ppm → m, a plane-2D joint per body flattened after each solve, QuickStep seeded before
 * each solve, contact ERP, contact CFM scaled by the pair's inverse masses, surface layer,
 * Approx1 friction, substeps and auto-disable. */
#include "bench.h"

#include <math.h>
#include <ode/ode.h>
#include <stdio.h>
#include <stdlib.h>

/// Thickness of every box along z, px: ODE needs a 3D box; equal thickness everywhere keeps
/// box–box contacts to the two z faces, four points a pair, as ODE gives in a 2D setup.
#define ODE_BOX_DEPTH_PX 32.0

typedef struct ode_scene {
    dWorldID world;
    dSpaceID space;
    dJointGroupID contact_group;
    dBodyID *bodies;              ///< per scene box; 0 for static boxes
    double *inv_mass;             ///< per scene box, 1/kg; 0 for static boxes (body data points here)
    int body_count;
    const bench_settings *set;
    int contacts;                 ///< contact points made in the current substep
    int pairs;                    ///< pairs handed to dCollide in the current substep
} ode_scene;

static int body_awake(dBodyID b) { return b && dBodyIsEnabled(b); }

static double body_inv_mass(dBodyID b) { return b ? *(const double *)dBodyGetData(b) : 0.0; }

/* Contact joints for one candidate pair; a pair with nothing awake is skipped, as the
 * raster broadphase skips sleeping and static pairs. */
static void near_callback(void *data, dGeomID g1, dGeomID g2)
{
    ode_scene *os = data;
    dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
    if (!body_awake(b1) && !body_awake(b2))
        return;

    const bench_settings *set = os->set;
    enum { MAX_CONTACTS = 8 };
    dContactGeom geoms[MAX_CONTACTS];
    int max = set->max_contacts_ode < MAX_CONTACTS ? set->max_contacts_ode : MAX_CONTACTS;
    int n = dCollide(g1, g2, max, geoms, sizeof geoms[0]);
    os->pairs++;
    /* PhysPix reads contact_cfm relative to the pair's reduced mass, so softness does not
     * depend on body size; the same here. */
    double inv_m = body_inv_mass(b1) + body_inv_mass(b2);
    double cfm = set->contact_cfm * (inv_m > 0 ? inv_m : 1.0);
    for (int i = 0; i < n; i++) {
        dContact c = {0};
        c.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
        c.surface.mu = set->friction; /* sqrt(fa·fb) with fa = fb */
        c.surface.soft_erp = set->contact_erp;
        c.surface.soft_cfm = cfm;
        if (set->restitution > 0.0) {
            c.surface.mode |= dContactBounce;
            c.surface.bounce = set->restitution;
            c.surface.bounce_vel = set->bounce_threshold / set->pixels_per_meter;
        }
        c.geom = geoms[i];
        dJointID j = dJointCreateContact(os->world, os->contact_group, &c);
        dJointAttach(j, b1, b2);
    }
    os->contacts += n;
}

/* The plane-2D joint holds z and the x/y angular velocities but leaves rotation drift to the
 * application: keep only the rotation about z and the in-plane motion, as PhysPix does. */
static void project_to_plane(ode_scene *os)
{
    for (int i = 0; i < os->body_count; i++) {
        dBodyID b = os->bodies[i];
        if (!body_awake(b))
            continue;
        const dReal *R = dBodyGetRotation(b), *w = dBodyGetAngularVel(b);
        const dReal *p = dBodyGetPosition(b), *v = dBodyGetLinearVel(b);
        double angle = atan2(R[4], R[0]), wz = w[2];
        double px = p[0], py = p[1], vx = v[0], vy = v[1];
        dMatrix3 flat;
        dRFromAxisAndAngle(flat, 0, 0, 1, angle);
        dBodySetRotation(b, flat);
        dBodySetAngularVel(b, 0, 0, wz);
        dBodySetPosition(b, px, py, 0);
        dBodySetLinearVel(b, vx, vy, 0);
    }
}

static void world_setup(ode_scene *os, const bench_settings *set)
{
    double ppm = set->pixels_per_meter;
    os->world = dWorldCreate();
    dWorldSetGravity(os->world, set->gravity_x / ppm, set->gravity_y / ppm, 0);
    dWorldSetQuickStepNumIterations(os->world, set->iterations);
    dWorldSetContactSurfaceLayer(os->world, set->contact_slop / ppm);
    dWorldSetAutoDisableFlag(os->world, set->allow_sleep ? 1 : 0);
    dWorldSetAutoDisableLinearThreshold(os->world, set->sleep_linear_speed / ppm);
    dWorldSetAutoDisableAngularThreshold(os->world, set->sleep_angular_speed);
    dWorldSetAutoDisableTime(os->world, set->sleep_time);
    dWorldSetAutoDisableSteps(os->world, 0);

    /* Cells from 2^-4 m (6 px) to 2^4 m (1600 px): the 16 and 32 px boxes land in fine
     * cells, the ground in the coarsest. */
    os->space = dHashSpaceCreate(0);
    dHashSpaceSetLevels(os->space, -4, 4);
    os->contact_group = dJointGroupCreate(0);
}

/* The box's geom in `space` (0: none), at its pose unless it gets a body; a terrain's box is
 * its solid part, below the empty top rows. */
static dGeomID box_geom(dSpaceID space, const bench_box *box, const bench_settings *set)
{
    double ppm = set->pixels_per_meter;
    double solid_h = box->h - box->empty_top;
    dGeomID g = dCreateBox(space, box->w / ppm, solid_h / ppm, ODE_BOX_DEPTH_PX / ppm);
    dMatrix3 R;
    dRFromAxisAndAngle(R, 0, 0, 1, box->angle);
    double c = cos(box->angle), s = sin(box->angle), down = 0.5 * box->empty_top; /* along the box's own y */
    dGeomSetPosition(g, (box->x - s * down) / ppm, (box->y + c * down) / ppm, 0);
    dGeomSetRotation(g, R);
    return g;
}

static void add_box(ode_scene *os, const bench_box *box, int index, const bench_settings *set)
{
    double ppm = set->pixels_per_meter;
    double lx = box->w / ppm, ly = box->h / ppm, lz = ODE_BOX_DEPTH_PX / ppm;
    dGeomID g = box_geom(os->space, box, set);
    dMatrix3 R;
    dRFromAxisAndAngle(R, 0, 0, 1, box->angle);
    if (box->is_static) {
        os->bodies[index] = 0;
        os->inv_mass[index] = 0.0;
        return;
    }
    dBodyID b = dBodyCreate(os->world);
    dMass m;
    dMassSetBoxTotal(&m, set->density * box->w * box->h, lx, ly, lz);
    dBodySetMass(b, &m);
    os->inv_mass[index] = 1.0 / m.mass;
    dBodySetData(b, &os->inv_mass[index]);
    dBodySetPosition(b, box->x / ppm, box->y / ppm, 0);
    dBodySetRotation(b, R);
    dGeomSetBody(g, b);
    dJointID plane = dJointCreatePlane2D(os->world, 0);
    dJointAttach(plane, b, 0);
    os->bodies[index] = b;
}

/* One step: `substeps` rounds of collide, seeded QuickStep, contact clean-up, projection. */
static void ode_step(ode_scene *os, double dt, int substeps, unsigned long *seed, double *collide_ms,
                     double *solve_ms)
{
    double h = dt / substeps;
    for (int k = 0; k < substeps; k++) {
        double t0 = bench_now_ms();
        os->contacts = 0;
        os->pairs = 0;
        dSpaceCollide(os->space, os, near_callback);
        double t1 = bench_now_ms();
        dRandSetSeed((*seed)++);
        dWorldQuickStep(os->world, h);
        dJointGroupEmpty(os->contact_group);
        project_to_plane(os);
        double t2 = bench_now_ms();
        *collide_ms += t1 - t0;
        *solve_ms += t2 - t1;
    }
}

/* ODE is initialised once for the whole run and closed at exit: its per-thread data is
 * shared with the library's ODE world on this thread, so it must outlive every run. */
static int ode_initialised;

void bench_ode_shutdown(void)
{
    if (ode_initialised)
        dCloseODE();
    ode_initialised = 0;
}

static int ode_init(void)
{
    if (!ode_initialised) {
        if (!dInitODE2(0) || !dAllocateODEDataForThread(dAllocateMaskAll)) {
            fprintf(stderr, "bench: ODE failed to initialise\n");
            return -1;
        }
        ode_initialised = 1;
    }
    return 0;
}

static int awake_count(const ode_scene *os)
{
    int n = 0;
    for (int i = 0; i < os->body_count; i++)
        n += body_awake(os->bodies[i]);
    return n;
}

int bench_run_ode(const bench_scene *scene, const bench_settings *set, bench_run *out)
{
    if (ode_init() != 0)
        return -1;
    ode_scene os = {.set = set, .body_count = scene->count};
    os.bodies = calloc((size_t)scene->count, sizeof *os.bodies);
    os.inv_mass = calloc((size_t)scene->count, sizeof *os.inv_mass);
    if (!os.bodies || !os.inv_mass) {
        free(os.bodies);
        free(os.inv_mass);
        fprintf(stderr, "bench: out of memory for the ODE bodies\n");
        return -1;
    }
    world_setup(&os, set);
    for (int i = 0; i < scene->count; i++)
        add_box(&os, &scene->boxes[i], i, set);

    unsigned long seed = 1;
    double contacts = 0.0, pairs = 0.0, collide_ms = 0.0, solve_ms = 0.0;
    for (out->settled = 0; out->settled < scene->settle_steps; out->settled++) {
        if (scene->settle_to_sleep && awake_count(&os) == 0)
            break;
        ode_step(&os, set->dt, set->substeps, &seed, &collide_ms, &solve_ms);
    }
    collide_ms = solve_ms = 0.0;
    out->awake_max = 0;
    for (int s = 0; s < scene->steps; s++) {
        double t0 = bench_now_ms(), collide_before = collide_ms;
        ode_step(&os, set->dt, set->substeps, &seed, &collide_ms, &solve_ms);
        out->step_ms[s] = bench_now_ms() - t0;
        if (out->narrow_ms)
            out->narrow_ms[s] = collide_ms - collide_before;
        contacts += os.contacts;
        pairs += os.pairs;
        int awake = awake_count(&os);
        out->awake_max = awake > out->awake_max ? awake : out->awake_max;
    }

    out->contacts_mean = contacts / scene->steps;
    out->pairs_mean = pairs / scene->steps;
    out->phase_ms[0] = 0.0; /* the hash space's pair search runs inside dSpaceCollide */
    out->phase_ms[1] = collide_ms / scene->steps;
    out->phase_ms[2] = solve_ms / scene->steps;
    out->backend = -1;
    out->awake_end = 0;
    out->lost = 0;
    out->tracked_drop = 0.0;
    for (int i = 0; i < scene->count; i++) {
        if (!os.bodies[i])
            continue;
        double y = dBodyGetPosition(os.bodies[i])[1] * set->pixels_per_meter;
        out->awake_end += body_awake(os.bodies[i]);
        out->lost += y > scene->ground_top;
        if (i == scene->tracked)
            out->tracked_drop = y - scene->boxes[i].y;
    }

    dJointGroupDestroy(os.contact_group);
    dSpaceDestroy(os.space);
    dWorldDestroy(os.world);
    free(os.bodies);
    free(os.inv_mass);
    return 0;
}

int bench_ode_collide_us(const bench_box *a, const bench_box *b, const bench_settings *set, int batches, int reps,
                         double *us_median, int *contacts)
{
    if (ode_init() != 0)
        return -1;
    double *batch_us = malloc((size_t)batches * sizeof *batch_us);
    if (!batch_us) {
        fprintf(stderr, "bench: out of memory for the dCollide batches\n");
        return -1;
    }
    /* Bodiless geoms outside any space: dCollide alone, as pp_world_collide runs the narrowphase alone. */
    dGeomID ga = box_geom(0, a, set), gb = box_geom(0, b, set);
    enum { MAX_CONTACTS = 8 };
    dContactGeom geoms[MAX_CONTACTS];
    int max = set->max_contacts_ode < MAX_CONTACTS ? set->max_contacts_ode : MAX_CONTACTS;
    int n = 0;
    for (int k = 0; k < batches; k++) {
        double t0 = bench_now_ms();
        for (int r = 0; r < reps; r++)
            n = dCollide(ga, gb, max, geoms, sizeof geoms[0]);
        batch_us[k] = (bench_now_ms() - t0) * 1e3 / reps;
    }
    *us_median = bench_median(batch_us, batches);
    *contacts = n;
    dGeomDestroy(ga);
    dGeomDestroy(gb);
    free(batch_us);
    return 0;
}
