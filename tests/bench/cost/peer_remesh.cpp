/* The Box2D 2.4 side of the destruction scene, as a game that keeps its terrain as a bitmap would do it: each
 * 64 × 64 px chunk meshed by marching squares, simplified by Douglas–Peucker at 1 px and handed to Box2D as
 * chain loops on one static body. A crater erases the bitmap's pixels, remeshes only the chunks they lie in
 * and wakes the crates around it. Frames as peer_box2d.cpp: metres at STAB_PX_PER_M, y up; crates are
 * polygon cores inside Box2D's 1 px skin with PhysPix's masses; sleep on. */
#include "cost.h"

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <new>
#include <utility>
#include <vector>

namespace {

constexpr double S = STAB_PX_PER_M;
constexpr int CHUNK = 64;
constexpr int NX = COST_TERRAIN_W / CHUNK, NY = COST_TERRAIN_H / CHUNK;
constexpr int SN = CHUNK + 2;             // samples a side: the chunk's pixels in a ring of empty ones
constexpr int HN = (SN - 1) * SN;         // crossing points on horizontal sample edges
constexpr int VN = SN * (SN - 1);         // and on vertical ones
constexpr double TOLERANCE = 1.0;         // Douglas–Peucker, px
constexpr double MIN_EDGE = 0.6;          // px: Box2D refuses chain edges under b2_linearSlop (0.5 px)
constexpr double WAKE_MARGIN = 4.0;       // px around the crater's box

struct Pt {
    double x, y;
};

// Distance from p to the segment a–b, px.
double segment_distance(Pt p, Pt a, Pt b)
{
    const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

class WakeAround : public b2QueryCallback {
  public:
    explicit WakeAround(const b2AABB &box) : box_(box) {}
    bool ReportFixture(b2Fixture *f) override
    {
        b2Body *b = f->GetBody();
        if (b->GetType() == b2_dynamicBody && b2TestOverlap(box_, f->GetAABB(0)))
            b->SetAwake(true);
        return true;
    }

  private:
    b2AABB box_;
};

} // namespace

struct cost_remesh {
    b2World world{b2Vec2(0.0f, (float)(-STAB_GRAVITY / S))};
    std::vector<uint8_t> solid;
    b2Body *terrain = nullptr;
    std::vector<std::vector<b2Fixture *>> chunks = std::vector<std::vector<b2Fixture *>>(NX * NY);
    std::vector<b2Body *> crates;
    // Scratch, kept between remeshes.
    std::vector<uint8_t> sample = std::vector<uint8_t>(SN * SN);
    std::vector<int> next = std::vector<int>(HN + VN);
    std::vector<Pt> loop, kept;
    std::vector<char> keep;
    std::vector<std::pair<size_t, size_t>> spans;
    std::vector<b2Vec2> verts;
};

namespace {

// The crossing point `id` of chunk (x0, y0), px: halfway between the two pixel centres its edge joins.
Pt crossing(int id, int x0, int y0)
{
    if (id < HN)
        return {x0 + (double)(id % (SN - 1)), y0 + id / (SN - 1) - 0.5};
    id -= HN;
    return {x0 + id % SN - 0.5, y0 + (double)(id / SN)};
}

// Douglas–Peucker over the closed loop r->loop into r->kept, split at the point farthest from the first.
void simplify(cost_remesh *r)
{
    const std::vector<Pt> &in = r->loop;
    const size_t n = in.size();
    size_t far = 0;
    double best = -1;
    for (size_t i = 1; i < n; i++) {
        const double d = std::hypot(in[i].x - in[0].x, in[i].y - in[0].y);
        if (d > best)
            best = d, far = i;
    }
    r->keep.assign(n, 0);
    r->keep[0] = r->keep[far] = 1;
    r->spans.assign({{0, far}, {far, n}}); // index n is point 0 again
    while (!r->spans.empty()) {
        const auto [a, b] = r->spans.back();
        r->spans.pop_back();
        size_t worst = 0;
        double dmax = TOLERANCE;
        for (size_t i = a + 1; i < b; i++) {
            const double d = segment_distance(in[i], in[a], in[b % n]);
            if (d > dmax)
                dmax = d, worst = i;
        }
        if (worst) {
            r->keep[worst] = 1;
            r->spans.push_back({a, worst});
            r->spans.push_back({worst, b});
        }
    }
    r->kept.clear();
    for (size_t i = 0; i < n; i++) {
        if (!r->keep[i])
            continue;
        const Pt &last = r->kept.empty() ? in[i] : r->kept.back();
        if (r->kept.empty() || std::hypot(in[i].x - last.x, in[i].y - last.y) >= MIN_EDGE)
            r->kept.push_back(in[i]);
    }
    while (r->kept.size() > 2 &&
           std::hypot(r->kept.back().x - r->kept[0].x, r->kept.back().y - r->kept[0].y) < MIN_EDGE)
        r->kept.pop_back();
}

void add_loop(cost_remesh *r, std::vector<b2Fixture *> &fixtures)
{
    simplify(r);
    if (r->kept.size() < 3) // a sliver under the tolerance
        return;
    r->verts.clear();
    for (const Pt &p : r->kept)
        r->verts.emplace_back((float)(p.x / S), (float)(-p.y / S));
    b2ChainShape chain;
    chain.CreateLoop(r->verts.data(), (int32)r->verts.size());
    b2FixtureDef fd;
    fd.shape = &chain;
    fd.friction = 0.6f;
    fixtures.push_back(r->terrain->CreateFixture(&fd));
}

/* Marching squares over one chunk, its pixels sampled at their centres inside a ring of empty samples, so that
 * every contour closes inside the chunk. Walking a cell's corners clockwise on screen (y down), a crossing
 * from solid to empty is an exit; each exit is joined to the next entry, so diagonal solid corners stay joined
 * (8-connected, as PhysPix's islands) and every loop runs with the solid on its left in Box2D's y-up frame:
 * outlines counter-clockwise, holes clockwise, each edge's outward normal on its right as chain loops want. */
void mesh_chunk(cost_remesh *r, int cx, int cy)
{
    std::vector<b2Fixture *> &fixtures = r->chunks[(size_t)(cy * NX + cx)];
    for (b2Fixture *f : fixtures)
        r->terrain->DestroyFixture(f);
    fixtures.clear();
    const int x0 = cx * CHUNK, y0 = cy * CHUNK;
    int solid = 0;
    for (int j = 0; j < CHUNK; j++)
        for (int i = 0; i < CHUNK; i++) {
            const uint8_t v = r->solid[(size_t)(y0 + j) * COST_TERRAIN_W + (size_t)(x0 + i)];
            r->sample[(size_t)((j + 1) * SN + i + 1)] = v;
            solid += v;
        }
    if (!solid)
        return;
    std::fill(r->next.begin(), r->next.end(), -1);
    for (int J = 0; J + 1 < SN; J++)
        for (int I = 0; I + 1 < SN; I++) {
            const uint8_t *s = &r->sample[(size_t)(J * SN + I)];
            const int c[4] = {s[0], s[1], s[SN + 1], s[SN]}; // TL, TR, BR, BL
            if (c[0] == c[1] && c[1] == c[2] && c[2] == c[3])
                continue;
            const int e[4] = {J * (SN - 1) + I, HN + J * SN + I + 1, (J + 1) * (SN - 1) + I, HN + J * SN + I};
            for (int k = 0; k < 4; k++) {
                if (!c[k] || c[(k + 1) & 3])
                    continue;
                for (int m = 1; m < 4; m++) {
                    const int q = (k + m) & 3;
                    if (!c[q] && c[(q + 1) & 3]) {
                        r->next[(size_t)e[q]] = e[k];
                        break;
                    }
                }
            }
        }
    for (int id = 0; id < HN + VN; id++) {
        if (r->next[(size_t)id] < 0)
            continue;
        r->loop.clear();
        int cur = id;
        do {
            r->loop.push_back(crossing(cur, x0, y0));
            const int n = r->next[(size_t)cur];
            r->next[(size_t)cur] = -1;
            cur = n;
        } while (cur >= 0 && cur != id);
        if (cur == id && r->loop.size() >= 3)
            add_loop(r, fixtures);
    }
}

void add_crate(cost_remesh *r, const stab_body &b)
{
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set((float)(b.x / S), (float)(-b.y / S));
    bd.angle = (float)-b.angle;
    b2Body *body = r->world.CreateBody(&bd);
    const double skin = b2_polygonRadius * S;
    b2PolygonShape box;
    box.SetAsBox((float)((0.5 * b.w - skin) / S), (float)((0.5 * b.h - skin) / S));
    b2FixtureDef fd;
    fd.shape = &box;
    fd.density = 1.0f; // replaced below by the whole box's mass: the core has less
    fd.friction = (float)b.friction;
    fd.restitution = (float)b.restitution;
    body->CreateFixture(&fd);
    b2MassData md;
    md.mass = (float)(b.density * b.w * b.h);
    md.center.SetZero();
    md.I = (float)(md.mass * (b.w * b.w + b.h * b.h) / 12.0 / (S * S));
    body->SetMassData(&md);
    r->crates.push_back(body);
}

} // namespace

extern "C" cost_remesh *cost_remesh_create(const cost_destruction *d)
{
    try {
        cost_remesh *r = new cost_remesh;
        r->solid.assign(d->terrain, d->terrain + (size_t)COST_TERRAIN_W * COST_TERRAIN_H);
        b2BodyDef bd;
        r->terrain = r->world.CreateBody(&bd);
        for (int cy = 0; cy < NY; cy++)
            for (int cx = 0; cx < NX; cx++)
                mesh_chunk(r, cx, cy);
        for (int i = 0; i < d->crates.count; i++)
            add_crate(r, d->crates.bodies[i]);
        return r;
    } catch (const std::bad_alloc &) {
        return nullptr;
    }
}

extern "C" void cost_remesh_erase(cost_remesh *r, double x, double y, double radius)
{
    const int i0 = std::max(0, (int)std::floor(x - radius)), i1 = std::min(COST_TERRAIN_W - 1, (int)std::ceil(x + radius));
    const int j0 = std::max(0, (int)std::floor(y - radius)), j1 = std::min(COST_TERRAIN_H - 1, (int)std::ceil(y + radius));
    int cx0 = NX, cx1 = -1, cy0 = NY, cy1 = -1; // chunks with an erased pixel
    for (int j = j0; j <= j1; j++)
        for (int i = i0; i <= i1; i++) {
            uint8_t &p = r->solid[(size_t)j * COST_TERRAIN_W + (size_t)i];
            const double dx = i + 0.5 - x, dy = j + 0.5 - y;
            if (!p || dx * dx + dy * dy > radius * radius)
                continue;
            p = 0;
            cx0 = std::min(cx0, i / CHUNK), cx1 = std::max(cx1, i / CHUNK);
            cy0 = std::min(cy0, j / CHUNK), cy1 = std::max(cy1, j / CHUNK);
        }
    for (int cy = cy0; cy <= cy1; cy++)
        for (int cx = cx0; cx <= cx1; cx++)
            mesh_chunk(r, cx, cy);
    // Box2D wakes only the crates whose touching contacts died with the old loops; a game wakes all around.
    const double m = radius + WAKE_MARGIN;
    b2AABB box;
    box.lowerBound.Set((float)((x - m) / S), (float)(-(y + m) / S));
    box.upperBound.Set((float)((x + m) / S), (float)(-(y - m) / S));
    WakeAround wake(box);
    r->world.QueryAABB(&wake, box);
}

extern "C" void cost_remesh_step(cost_remesh *r)
{
    r->world.Step((float)STAB_DT, 8, 3);
}

extern "C" int cost_remesh_awake(const cost_remesh *r)
{
    int n = 0;
    for (const b2Body *b : r->crates)
        n += b->IsAwake();
    return n;
}

extern "C" void cost_remesh_counts(const cost_remesh *r, int *loops, int *vertices)
{
    *loops = *vertices = 0;
    for (const auto &fixtures : r->chunks)
        for (const b2Fixture *f : fixtures) {
            *loops += 1;
            *vertices += static_cast<const b2ChainShape *>(f->GetShape())->m_count - 1; // a loop repeats its first
        }
}

extern "C" void cost_remesh_destroy(cost_remesh *r)
{
    delete r;
}
