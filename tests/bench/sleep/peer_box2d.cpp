/* The Box2D 2.4 peer of bench_sleep: the same crates, platform and boxes in metres (100 px a metre), y up,
 * each polygon's core moved in by Box2D's 1 px skin so that crates placed touching touch. Box2D's defaults:
 * 8 velocity and 3 position iterations, sleep on. */
#include "peer.h"

#include <box2d/box2d.h>

#include <algorithm>
#include <ctime>
#include <vector>

namespace {

constexpr float S = 100.0f; /* px a metre */

double now_ms()
{
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

b2Body *add_box(b2World &w, bool dynamic, float width, float height, float x, float y)
{
    b2BodyDef bd;
    bd.type = dynamic ? b2_dynamicBody : b2_staticBody;
    bd.position.Set(x / S, -y / S);
    b2Body *b = w.CreateBody(&bd);
    b2PolygonShape box;
    const float skin = b2_polygonRadius * S;
    box.SetAsBox((0.5f * width - skin) / S, (0.5f * height - skin) / S);
    b->CreateFixture(&box, 1.0f);
    return b;
}

int awake_count(b2World &w)
{
    int n = 0;
    for (b2Body *b = w.GetBodyList(); b; b = b->GetNext())
        n += b->GetType() == b2_dynamicBody && b->IsAwake();
    return n;
}

} // namespace

double sleep_box2d_ms(const sleep_scene *s, int blocks, int *awake)
{
    b2World w(b2Vec2(0.0f, -9.8f));
    const float dt = 1.0f / 60.0f;
    if (s->crates > 0) {
        add_box(w, false, s->floor_w, s->floor_h, 0.5f * s->floor_w, s->floor_top + 0.5f * s->floor_h);
        const int cols = (s->crates + s->stack - 1) / s->stack;
        for (int i = 0; i < s->crates; i++)
            add_box(w, true, s->crate, s->crate, 0.5f * s->floor_w + (i / s->stack - (cols - 1) * 0.5f) * s->pitch,
                    s->floor_top - 0.5f * s->crate - (i % s->stack) * s->crate);
        for (int k = 0; k < 600 && (k == 0 || awake_count(w) > 0); k++)
            w.Step(dt, 8, 3);
    }
    std::vector<b2Body *> movers;
    if (s->movers > 0) {
        add_box(w, false, 400.0f, 16.0f, 300.0f, s->platform_top + 8.0f);
        for (int i = 0; i < s->movers; i++)
            movers.push_back(add_box(w, true, 16.0f, 16.0f, 150.0f + 40.0f * i, s->platform_top - 60.0f));
    }
    std::vector<double> ms;
    int step = 0;
    for (int b = 0; b < blocks; b++) {
        double spent = 0;
        for (int k = 0; k < s->block; k++, step++) {
            if (step % 30 == 0)
                for (b2Body *m : movers)
                    m->SetLinearVelocity(b2Vec2(0.0f, 3.0f)), m->SetAwake(true);
            const double t0 = now_ms();
            w.Step(dt, 8, 3);
            spent += now_ms() - t0;
        }
        ms.push_back(spent / s->block);
    }
    std::sort(ms.begin(), ms.end());
    *awake = awake_count(w);
    return ms[ms.size() / 2];
}
