/* bench_sleep's scene as numbers, shared by PhysPix (main.c) and the peers (peer_box2d.cpp, peer_chipmunk.c);
 * px, y down. */
#ifndef PP_BENCH_SLEEP_PEER_H
#define PP_BENCH_SLEEP_PEER_H

#ifdef __cplusplus
extern "C" {
#endif

/// N crates at rest in stacks on a terrain; `movers` boxes over a platform of their own above them.
typedef struct sleep_scene {
    int crates, movers;   ///< sleeping crates, awake boxes
    int crate, stack;     ///< crate side, px; crates a stack
    float pitch;          ///< px between stacks
    float floor_w, floor_h, floor_top; ///< terrain size and its top's y, px
    float platform_top;   ///< the platform's top y, px
    int block;            ///< steps a timed block
} sleep_scene;

/// Box2D 2.4: settle the crates to sleep, add the boxes, time `blocks` blocks of steps (the boxes thrown up
/// every 30 steps, outside the clock); the median block's ms per step; *awake = bodies awake at the end.
double sleep_box2d_ms(const sleep_scene *s, int blocks, int *awake);
/// Chipmunk 7, the same (10 iterations; asleep after 0.5 s under 5 px/s, as PhysPix); -1 without memory.
double sleep_chipmunk_ms(const sleep_scene *s, int blocks, int *awake);

#ifdef __cplusplus
}
#endif

#endif
