/* The settings both engines run with, taken from the library's defaults, and the lines every
 * engine-against-engine bench prints first: the machine and those settings. */
#include "bench.h"
#include "machine.h"
#include "physpix.h"

#include <ctype.h>
#include <math.h>
#include <ode/ode.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

bench_settings bench_settings_from_defaults(void)
{
    pp_world_def w = pp_world_def_default();
    pp_body_def b = pp_body_def_default();
    return (bench_settings){
        .dt = 1.0 / 60.0,
        .gravity_x = w.gravity.x,
        .gravity_y = w.gravity.y,
        .substeps = w.substeps,
        .iterations = w.solver_iterations,
        .pixels_per_meter = w.pixels_per_meter,
        .contact_erp = w.contact_erp,
        .contact_cfm = w.contact_cfm,
        .contact_slop = w.contact_slop,
        .friction = b.friction,
        .restitution = b.restitution,
        .bounce_threshold = w.bounce_threshold,
        .density = b.density,
        .allow_sleep = w.allow_sleep != 0,
        .sleep_linear_speed = w.sleep_linear_speed,
        .sleep_angular_speed = w.sleep_angular_speed,
        .sleep_time = w.sleep_time,
        .max_contacts_ode = 4,
    };
}

void bench_print_machine(const char *title)
{
    char model[256];
    bench_cpu_model(model, sizeof model);
    uint32_t v = pp_version();
    printf("PhysPix %u.%u.%u %s\n", v / 10000, v / 100 % 100, v % 100, title);
    printf("machine: %ld cpus online, %s\n", sysconf(_SC_NPROCESSORS_ONLN), model);
    printf("ODE: %s precision\n", dCheckConfiguration("ODE_double_precision") ? "double" : "single");
}

void bench_print_settings(const bench_settings *s)
{
    pp_world_def w = pp_world_def_default();
    printf("settings: dt 1/%.0f s, gravity (%.0f, %.0f) px/s², %d substeps, QuickStep %d iterations,\n"
           "          %.0f px/m, contact ERP %.2f, CFM %.0e, slop %.1f px, friction %.2f (Approx1), "
           "restitution %.2f, density %.1f\n"
           "          sleep %s (%.1f px/s, %.2f rad/s, %.2f s); raster: backend %d, normal %d, contact mode %d, "
           "stride %d; analytic: <= %d contacts/pair, hash space\n",
           1.0 / s->dt, s->gravity_x, s->gravity_y, s->substeps, s->iterations, s->pixels_per_meter, s->contact_erp,
           s->contact_cfm, s->contact_slop, s->friction, s->restitution, s->density, s->allow_sleep ? "on" : "off",
           s->sleep_linear_speed, s->sleep_angular_speed, s->sleep_time, (int)w.backend, (int)w.normal_method,
           (int)w.contact_mode, w.raster_stride, s->max_contacts_ode);
}

double bench_median(double *v, int n)
{
    if (n <= 0)
        return 0.0;
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int bench_matches(const char *hay, const char *needle)
{
    if (!needle)
        return 1;
    const size_t n = strlen(needle);
    for (const char *h = hay; *h; h++) {
        size_t k = 0;
        while (k < n && h[k] && tolower((unsigned char)h[k]) == tolower((unsigned char)needle[k]))
            k++;
        if (k == n)
            return 1;
    }
    return n == 0;
}

const char *bench_fmt(char *buf, size_t n, const char *format, double v)
{
    if (isfinite(v))
        snprintf(buf, n, format, v);
    else
        snprintf(buf, n, "-");
    return buf;
}

void bench_csv_field(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, ",%.6g", v);
    else
        fprintf(f, ",");
}
