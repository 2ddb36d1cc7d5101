/* tether — a small, fast 2D game physics engine. The whole public C API.
 *
 * Conventions: every function is tt_<object>_<verb>; objects inside a world
 * are generational handles, checked on every call; calls that can fail
 * return tt_result and leave a readable message in tt_last_error(world);
 * NaN and Inf are refused at the door, so they never enter a world.
 * Units are yours; metres, seconds and kilograms are recommended. */
#ifndef TETHER_H
#define TETHER_H

#include "tether/base.h"
#include "tether/world.h"
#include "tether/particle.h"
#include "tether/spring.h"
#include "tether/constraint.h"
#include "tether/composite.h"
#include "tether/collide.h"
#include "tether/clock.h"
#include "tether/rewind.h"
#include "tether/journal.h"
#include "tether/mask.h"
#include "tether/terrain.h"

#endif
