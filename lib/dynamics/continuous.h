/* Continuous collision: fast bodies swept along their substep's motion so they cannot pass
 * through thin walls between two collision checks (see continuous.c). */
#ifndef PP_CONTINUOUS_H
#define PP_CONTINUOUS_H

#include "world.h"

/* Before a substep's solve: remember where every body that may be swept starts. */
pp_status continuous_begin(world *wd);

/* After the solve and the pose read-back: stop each fast body at its first hit along its path. Out of memory
 * for the bodies near a path: PP_ERR_OUT_OF_MEMORY (the step is undone). */
pp_status continuous_end(world *wd);

void continuous_free(sweep_set *s);

#endif
