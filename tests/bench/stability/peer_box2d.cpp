/* The Box2D 2.4 peer: the engine-neutral bodies as Box2D bodies in metres (STAB_PX_PER_M px a metre), y up,
 * so a PhysPix pose (x, y, a) is (x, −y, −a) / scale here. Masses are PhysPix's (density × area in px²) with
 * the analytic inertia. A polygon's core is its outline moved in by the skin Box2D rounds it with (1 px; less
 * on a thin card), so that bodies placed exactly touching touch. Box2D's defaults otherwise: 8 velocity and 3
 * position iterations, friction sqrt(fa·fb) and restitution max(ea, eb) as in PhysPix. */
#include "peers.h"

#include <box2d/box2d.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

constexpr double S = STAB_PX_PER_M;

struct B2Scene {
    b2World world{b2Vec2(0.0f, (float)(-STAB_GRAVITY / S))};
    std::vector<b2Body *> bodies;
};

/* The radius of a polygon's skin: Box2D's own (1 px), or a quarter of a thin box's thickness, so that the
 * core keeps some thickness (a 2 px card gets 0.5 px). */
double skin(const stab_body &b)
{
    const double r = b2_polygonRadius * S;
    if (b.shape != STAB_BOX)
        return r;
    const double thin = 0.25 * (b.w < b.h ? b.w : b.h);
    return thin < r ? thin : r;
}

/* Polygon vertices in metres, y up, each edge moved in by the skin so that the rounded shape Box2D collides
 * with has the body's outline: analytic shapes placed exactly touching then touch in Box2D too. */
int core_vertices(const stab_body &b, double r, b2Vec2 *v)
{
    if (b.shape == STAB_BOX) {
        const double hx = 0.5 * b.w - r, hy = 0.5 * b.h - r;
        const double x[4] = {-hx, hx, hx, -hx}, y[4] = {-hy, -hy, hy, hy};
        for (int i = 0; i < 4; i++)
            v[i].Set((float)(x[i] / S), (float)(-y[i] / S));
        return 4;
    }
    double sign = 0; /* the winding, so that edge normals point out */
    for (int i = 0; i < b.nverts; i++) {
        const int j = (i + 1) % b.nverts;
        sign += b.vx[i] * b.vy[j] - b.vx[j] * b.vy[i];
    }
    sign = sign > 0 ? 1 : -1;
    for (int i = 0; i < b.nverts; i++) {
        const int h = (i + b.nverts - 1) % b.nverts, j = (i + 1) % b.nverts;
        double n1x = sign * (b.vy[i] - b.vy[h]), n1y = -sign * (b.vx[i] - b.vx[h]);
        double n2x = sign * (b.vy[j] - b.vy[i]), n2y = -sign * (b.vx[j] - b.vx[i]);
        const double l1 = std::hypot(n1x, n1y), l2 = std::hypot(n2x, n2y);
        n1x /= l1, n1y /= l1, n2x /= l2, n2y /= l2;
        const double k = r / (1 + n1x * n2x + n1y * n2y); /* the corner moves along the bisector */
        v[i].Set((float)((b.vx[i] - k * (n1x + n2x)) / S), (float)(-(b.vy[i] - k * (n1y + n2y)) / S));
    }
    return b.nverts;
}

/* Polygon area, px², and inertia about the origin (the centroid), mass·px², of density 1. */
void poly_mass(const stab_body &b, double *area, double *inertia)
{
    double a = 0, i2 = 0;
    for (int i = 0; i < b.nverts; i++) {
        const int j = (i + 1) % b.nverts;
        const double cr = b.vx[i] * b.vy[j] - b.vx[j] * b.vy[i];
        a += cr;
        i2 += cr * (b.vx[i] * b.vx[i] + b.vx[i] * b.vx[j] + b.vx[j] * b.vx[j] + b.vy[i] * b.vy[i] +
                    b.vy[i] * b.vy[j] + b.vy[j] * b.vy[j]);
    }
    *area = std::fabs(0.5 * a);
    *inertia = std::fabs(i2 / 12.0);
}

/* The analytic shape's mass (density × px²) and inertia about the origin, in Box2D's units. */
b2MassData mass_data(const stab_body &b)
{
    double area, in;
    if (b.shape == STAB_DISC) {
        area = 3.14159265358979323846 * b.radius * b.radius;
        in = 0.5 * area * b.radius * b.radius;
    } else if (b.shape == STAB_BOX) {
        area = b.w * b.h;
        in = area * (b.w * b.w + b.h * b.h) / 12.0;
    } else {
        poly_mass(b, &area, &in);
    }
    b2MassData md;
    md.mass = (float)(b.density * area);
    md.center.SetZero();
    md.I = (float)(b.density * in / (S * S));
    return md;
}

void add_fixture(b2Body *body, const stab_body &b)
{
    b2PolygonShape poly;
    b2CircleShape circle;
    b2FixtureDef fd;
    if (b.shape == STAB_DISC) {
        circle.m_radius = (float)(b.radius / S);
        fd.shape = &circle;
    } else {
        b2Vec2 v[STAB_MAX_VERTS];
        const double r = skin(b);
        poly.Set(v, core_vertices(b, r, v));
        poly.m_radius = (float)(r / S);
        fd.shape = &poly;
    }
    fd.density = 1.0f; /* replaced below by the analytic shape's mass: a core polygon has less */
    fd.friction = (float)b.friction;
    fd.restitution = (float)b.restitution;
    body->CreateFixture(&fd);
    if (!b.is_static) {
        const b2MassData md = mass_data(b);
        body->SetMassData(&md);
    }
}

void *create(const stab_engine *, const stab_scene *s)
{
    B2Scene *w = new B2Scene;
    w->world.SetAllowSleeping(false);
    for (int i = 0; i < s->count; i++) {
        const stab_body &b = s->bodies[i];
        b2BodyDef bd;
        bd.type = b.is_static ? b2_staticBody : b2_dynamicBody;
        bd.position.Set((float)(b.x / S), (float)(-b.y / S));
        bd.angle = (float)-b.angle;
        bd.linearVelocity.Set((float)(b.vel_x / S), (float)(-b.vel_y / S));
        bd.bullet = b.bullet != 0;
        bd.allowSleep = false;
        b2Body *body = w->world.CreateBody(&bd);
        add_fixture(body, b);
        w->bodies.push_back(body);
    }
    return w;
}

int step(void *p)
{
    static_cast<B2Scene *>(p)->world.Step((float)STAB_DT, 8, 3);
    return 0;
}

void pose(void *p, int i, stab_pose *out)
{
    const b2Body *b = static_cast<B2Scene *>(p)->bodies[(size_t)i];
    out->x = b->GetPosition().x * S;
    out->y = -b->GetPosition().y * S;
    out->angle = -b->GetAngle();
}

/* Inertia about the centre of mass (Box2D's is about the body origin), in mass·px². */
void mass(void *p, int i, double *m, double *inertia)
{
    const b2Body *b = static_cast<B2Scene *>(p)->bodies[(size_t)i];
    const b2Vec2 c = b->GetLocalCenter();
    *m = b->GetMass();
    *inertia = (b->GetInertia() - b->GetMass() * b2Dot(c, c)) * S * S;
}

void destroy(void *p)
{
    delete static_cast<B2Scene *>(p);
}

} // namespace

extern "C" stab_engine stab_engine_box2d(void)
{
    stab_engine e{};
    std::snprintf(e.name, sizeof e.name, "Box2D %d.%d", b2_version.major, b2_version.minor);
    e.create = create;
    e.step = step;
    e.pose = pose;
    e.mass = mass;
    e.destroy = destroy;
    e.iterations = 8;
    return e;
}

extern "C" const char *stab_box2d_version(void)
{
    static char v[32];
    std::snprintf(v, sizeof v, "%d.%d.%d", b2_version.major, b2_version.minor, b2_version.revision);
    return v;
}
