/* The benchmark's shared vocabulary: a scene as a list of boxes, the solver settings both
 * engines run with, and what one timed run of one engine returns. */
#ifndef PP_BENCH_H
#define PP_BENCH_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/// One box of a scene; the same numbers build a raster body and an ODE dCreateBox.
typedef struct bench_box {
    double x, y;          ///< centre, px (world y down)
    int32_t w, h;         ///< size, px
    double angle;         ///< rotation, radians (+x turns toward +y)
    int is_static;        ///< nonzero: never moves (ground)
    int32_t empty_top;    ///< static boxes: empty rows at the bitmap's top (a terrain's sky), px; ODE's box is the rest
} bench_box;

/// A named scene: its boxes, how long it runs, and which box's drop is the sanity number.
typedef struct bench_scene {
    const char *name;     ///< CSV name, e.g. "pyramid"
    bench_box *boxes;     ///< owned; freed by bench_scene_free
    int count;            ///< boxes in all
    int dynamic_count;    ///< boxes that move
    int steps;            ///< pp_world_step calls per run
    int tracked;          ///< index of the box whose final drop is reported, or -1
    double ground_top;    ///< y of the ground's top edge, px: a box whose centre ends below it is lost
    int settle_steps;     ///< untimed steps before the timed ones (0: none)
    int settle_to_sleep;  ///< nonzero: settling ends as soon as no body is awake
} bench_scene;

/// Settings both engines share, taken from pp_world_def_default() and pp_body_def_default().
typedef struct bench_settings {
    double dt;                  ///< step, s
    double gravity_x, gravity_y;///< px/s²
    int substeps;               ///< solver steps per step
    int iterations;             ///< QuickStep iterations
    double pixels_per_meter;    ///< px/m handed to ODE
    double contact_erp;         ///< contact ERP, 0..1
    double contact_cfm;         ///< contact CFM, non-dimensional
    double contact_slop;        ///< px, ODE's contact surface layer
    double friction;            ///< Coulomb coefficient of every box (pairs: sqrt(fa·fb))
    double restitution;         ///< of every box (pairs: max)
    double bounce_threshold;    ///< px/s, approach speed below which restitution is ignored
    double density;             ///< mass units per solid pixel
    int allow_sleep;            ///< nonzero: auto-disable resting bodies
    double sleep_linear_speed;  ///< px/s
    double sleep_angular_speed; ///< rad/s
    double sleep_time;          ///< s
    int max_contacts_ode;       ///< contacts per pair asked of dCollide (ODE baseline only)
} bench_settings;

/// What one run of one engine measured.
typedef struct bench_run {
    double *step_ms;        ///< per-step wall time, ms; caller-owned, scene->steps long
    double *narrow_ms;      ///< optional per-step narrowphase ms (ODE: dSpaceCollide); caller-owned, or NULL
    double contacts_mean;   ///< mean contact points of the last substep, per step
    double pairs_mean;      ///< mean pairs tested in the last substep, per step (ODE: pairs handed to dCollide)
    double tracked_drop;    ///< final y − initial y of the tracked box, px (down is positive)
    double phase_ms[3];     ///< mean broadphase, narrowphase, solver ms per step (ODE: 0, dSpaceCollide, solve)
    int awake_end;          ///< bodies awake after the last step
    int awake_max;          ///< most bodies awake after any timed step
    int settled;            ///< untimed steps run before timing
    int lost;               ///< dynamic boxes whose centre ended below the ground's top edge
    int backend;            ///< PhysPix: pp_backend that ran the narrowphase; ODE: -1
} bench_run;

/// Monotonic clock, milliseconds.
double bench_now_ms(void);

/// The library's default world and body settings, copied for the ODE baseline.
bench_settings bench_settings_from_defaults(void);
/// Print the machine (CPU model, CPUs online), the library version and ODE's precision; title names the bench.
void bench_print_machine(const char *title);
/// Print the settings both engines run with, three lines.
void bench_print_settings(const bench_settings *set);
/// Median of v[0..n) (sorts v); 0 when n is 0.
double bench_median(double *v, int n);
/// Whether `needle` (NULL: anything) occurs in `hay`, ignoring case: the benches' --only and --engine.
int bench_matches(const char *hay, const char *needle);
/// v printed with `format` into buf (n bytes), or "-" when v is not finite (unmeasured); returns buf.
const char *bench_fmt(char *buf, size_t n, const char *format, double v);
/// Append ",v" to a CSV line, or "," when v is not finite.
void bench_csv_field(FILE *f, double v);

/// The 10-row pyramid of 16 px boxes on a static ground (55 boxes).
int bench_scene_pyramid(bench_scene *out, int steps);
/// 500 crates of 32 px in a 25 × 20 grid above a static ground.
int bench_scene_rain(bench_scene *out, int steps);
/// Free a scene's boxes.
void bench_scene_free(bench_scene *scene);

/// Run a scene with PhysPix raster bodies; 0 on success, else prints why and returns -1.
int bench_run_physpix(const bench_scene *scene, const bench_settings *set, bench_run *out);
/// Run a scene with ODE's analytic boxes; 0 on success, else prints why and returns -1.
int bench_run_ode(const bench_scene *scene, const bench_settings *set, bench_run *out);
/// Median time of one dCollide on two ODE boxes built as bench_run_ode builds them, µs, over `batches`
/// batches of `reps` calls; contacts receives one call's points (at most set->max_contacts_ode). 0 or -1.
int bench_ode_collide_us(const bench_box *a, const bench_box *b, const bench_settings *set, int batches, int reps,
                         double *us_median, int *contacts);
/// Release ODE if bench_run_ode or bench_ode_collide_us initialised it.
void bench_ode_shutdown(void);

#endif
