/* Small 2D helpers shared by the library (double precision inside, float at the ABI). */
#ifndef PP_MATH2D_H
#define PP_MATH2D_H

#include <math.h>

#define PP_PI 3.14159265358979323846

typedef struct dvec2 {
    double x, y;
} dvec2;

/* fmax and fmin inline: GCC leaves them calls into libm for their NaN and signed-zero rules. The same result
 * as theirs (a NaN loses to a number) but for a zero against a zero of the other sign. */
static inline double dmax(double a, double b) { return a > b || b != b ? a : b; }
static inline double dmin(double a, double b) { return a < b || b != b ? a : b; }

static inline dvec2 dv(double x, double y) { return (dvec2){x, y}; }
static inline dvec2 dv_add(dvec2 a, dvec2 b) { return dv(a.x + b.x, a.y + b.y); }
static inline dvec2 dv_sub(dvec2 a, dvec2 b) { return dv(a.x - b.x, a.y - b.y); }
static inline dvec2 dv_scale(dvec2 a, double s) { return dv(a.x * s, a.y * s); }
static inline double dv_dot(dvec2 a, dvec2 b) { return a.x * b.x + a.y * b.y; }
static inline double dv_norm(dvec2 a) { return hypot(a.x, a.y); }
/* Rotate by angle (radians); +x turns toward +y. */
static inline dvec2 dv_rot(dvec2 a, double c, double s) { return dv(c * a.x - s * a.y, s * a.x + c * a.y); }
/* Rotate by −angle. */
static inline dvec2 dv_unrot(dvec2 a, double c, double s) { return dv(c * a.x + s * a.y, -s * a.x + c * a.y); }

/* An angle's cos and sin from its half's, as ODE's quaternion (cos ½a, 0, 0, sin ½a) turns about z: the solver's
 * rotation and a body's (cos, sin) come from one sincos. Every body's (cos, sin) is made so, bit for bit alike. */
static inline void turn_from_half(double half_c, double half_s, double *c, double *s)
{
    *c = half_c * half_c - half_s * half_s;
    *s = 2.0 * half_c * half_s;
}
static inline void angle_cos_sin(double angle, double *c, double *s)
{
    turn_from_half(cos(0.5 * angle), sin(0.5 * angle), c, s);
}

static inline int finite2(float x, float y) { return isfinite(x) && isfinite(y); }

#endif
