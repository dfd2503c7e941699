/* The peer engines of the stability benchmark, Box2D 2.4 (C++, peer_box2d.cpp) and Chipmunk 7
 * (peer_chipmunk.c), as stab_engine rows over the same engine-neutral scenes. Only bench_stability links
 * them; stability.h does not include this header. */
#ifndef PP_BENCH_STABILITY_PEERS_H
#define PP_BENCH_STABILITY_PEERS_H

#include "stability.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The Box2D 2.4 row: metres at STAB_PX_PER_M, y up, 8 velocity and 3 position iterations, sleep off.
stab_engine stab_engine_box2d(void);
/// Box2D's version, e.g. "2.4.1".
const char *stab_box2d_version(void);
/// A Chipmunk 7 row with `iterations` solver iterations (Chipmunk's default is 10), px, sleep off.
stab_engine stab_engine_chipmunk(int iterations);
/// Chipmunk's version, e.g. "7.0.3".
const char *stab_chipmunk_version(void);

#ifdef __cplusplus
}
#endif

#endif
