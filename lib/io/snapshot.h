/* Snapshots: a world's whole state in a folder, world.json plus PNG planes, written under a temporary
 * name and swapped in by rename, so a crash never leaves half a snapshot. Everything is saved exactly
 * (doubles printed to read back bit for bit, ODE's state as it was set, the slot tables and the bodies'
 * creation order, which ODE's body list follows), so a loaded world steps on as the saved one would.
 * Saving is snapshot_write.c, loading snapshot_read.c; this header holds what both agree on. */
#ifndef PP_SNAPSHOT_H
#define PP_SNAPSHOT_H

/* world.json's "format" and "version": the loader takes only this format at this version. */
#define SNAPSHOT_FORMAT "physpix-snapshot"
#define SNAPSHOT_VERSION 1

/* pp_event_type by index as world.json names it ("" at 0, which is none), NULL-terminated; in snapshot_write.c. */
extern const char *const event_names[];

/* A joint's state beyond its def, in the order write_joint saves it: local anchors (4), axis in a (2), ref, length,
 * slider offset, the last attach's frame (7) and ODE poses (6), ODE's feedback (6), pinned flags (2). */
enum { JOINT_STATE_DOUBLES = 31 };

/* A held pair's contact as 15 numbers: point, normal, depth, pixel count, impulse, then both bodies' centres of
 * mass and rotations when the raster found it. */
enum { HELD_NUMBERS = 15 };
/* A touching pair's saved contact: point, normal, depth, pixel count, impulse (the first of a held one's). */
enum { SAVED_CONTACT_NUMBERS = 7 };

#endif
