// Binding points of the spinlock experiment, shared by micro/experiments/spinlock.cpp and
// spinlock.frag. The per-pixel array itself uses shaders/storage/bindings.h.
#ifndef OITBENCH_SPINLOCK_BINDINGS_H
#define OITBENCH_SPINLOCK_BINDINGS_H

#define SPINLOCK_LOCK_IMAGE_UNIT 1   // r32ui: 1 while a fragment holds the pixel
#define SPINLOCK_COUNT_IMAGE_UNIT 2  // r32ui: entries inserted into the pixel's array
#define SPINLOCK_STATS_BINDING 1     // SSBO: fragments that gave up at SPIN_CAP

#endif
