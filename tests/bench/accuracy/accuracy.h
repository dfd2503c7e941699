/* The accuracy benchmark's vocabulary: how long each measurement runs, what one world setting
 * measured, and the runs that measure it (runs.c). Scenes come from tests/bench (bench.h). */
#ifndef PP_BENCH_ACCURACY_H
#define PP_BENCH_ACCURACY_H

#include "analytic.h"
#include "bench.h"
#include "physpix.h"

#define ACC_DT (1.0 / 60.0)    ///< every run steps at 60 Hz, s
#define ACC_SIDE 16            ///< box side of the pyramid and the tower, px
#define ACC_STAND_PX (ACC_SIDE / 4.0) ///< a stack stands while no box moves more than this, px
#define ACC_BOUNCES 10         ///< bounces of the elastic-bounce energy run

/// How long each measurement runs (full or --quick).
typedef struct acc_plan {
    double settle_s;   ///< a stack settles this long before its pose is taken, s
    double horizon_s;  ///< then it is watched this long, s (the stability bar in tests/bench/README.md: 60)
    double contact_s;  ///< contacts are read over the last this-many seconds, s
    int rain_steps;    ///< steps of the timing-only rain scene
    double budget_s;   ///< wall time a stack run may take before it is cut short (exact solver), s
} acc_plan;

/// One stack run (pyramid or tower) with sleep off.
typedef struct acc_stack {
    double ms_median;      ///< wall time of one pp_world_step, ms: the least of six blocks' medians
    double sim_s;          ///< simulated time reached, s (< settle + horizon: cut short by the budget)
    int complete;          ///< nonzero: the whole settle + horizon ran, or a pose diverged
    int nan;               ///< nonzero: a pose became NaN or infinite
    /* NaN in these three: the run never reached the settle time. */
    double settle_shift;   ///< largest horizontal offset of a box from its built x at the settle time, px
    double sag;            ///< largest downward offset of a box from its built y at the settle time, px
    double drift;          ///< largest displacement of a box from its settled pose over the horizon, px
    double pen_sum;        ///< sum of contact depths read over the last contact_s, px
    double pen_max;        ///< deepest of them, px
    long pen_count;        ///< how many
    double contacts_mean;  ///< contact points per step over the run
} acc_stack;

/// Everything measured for one world setting.
typedef struct acc_metrics {
    int collide_ok;                              ///< nonzero: every analytic pair gave contacts
    double normal_med[ANALYTIC_FAMILY_COUNT];    ///< normal error median per family, degrees
    double normal_p95[ANALYTIC_FAMILY_COUNT];    ///< normal error 95th percentile per family, degrees
    double depth_med[ANALYTIC_FAMILY_COUNT];     ///< depth error median per family, px
    acc_stack pyramid, tower;
    double rain_ms;                              ///< median ms/step of the rain scene
    int rain_steps;                              ///< rain steps run (fewer than planned: cut by the budget)
    int backend_ran;                             ///< pp_backend of the pyramid's last step
    double energy_pct;                           ///< largest |E − E0| / E0 at the apexes after each bounce, %
    double energy_final_pct;                     ///< (E − E0) / E0 at the last apex, % (signed)
    int bounces;                                 ///< bounces seen (ACC_BOUNCES unless the ball came to rest)
    double bounce_side_speed;                    ///< largest sideways speed at an apex, px/s (a straight drop: 0)
    double momentum_pct;                         ///< largest |p_after − p_before| / |p_before| of the cases, %
    int momentum_collided;                       ///< nonzero: every free-collision case did collide
} acc_metrics;

/// Normal and depth errors on the analytic cases (pp_world_collide, no stepping); 0, or -1 if the set-up failed.
int acc_measure_collide(const pp_world_def *def, acc_metrics *m);
/// A stack scene stepped with sleep off: time per step, settling, drift, resting contacts; 0 or -1.
int acc_measure_stack(const bench_scene *scene, const pp_world_def *def, const acc_plan *plan, acc_stack *out,
                      int *backend_ran);
/// Median ms/step of a scene with sleep off over its steps, or those run within budget_s; 0 or -1.
int acc_measure_timing(const bench_scene *scene, const pp_world_def *def, double budget_s, double *ms_median,
                       int *steps_done);
/// Energy of an elastic ball (restitution 1, bounce threshold 0) at the apex after each bounce; 0 or -1.
int acc_measure_bounce(const pp_world_def *def, acc_metrics *m);
/// Linear momentum before and after free collisions with gravity 0; 0 or -1.
int acc_measure_momentum(const pp_world_def *def, acc_metrics *m);

/// The 10-box tower: an aligned column of ACC_SIDE px boxes on a static ground.
int acc_scene_tower(bench_scene *out, int steps);

/// The q-quantile (0..1) of n values by nearest rank (as tests/c/helpers.h); sorts v in place.
double acc_quantile(double *v, int n, double q);

#endif
