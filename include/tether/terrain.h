/* tether — terrains: carvable pixel masks placed in a world, that particles
 * (and so ropes, cloth, lattices) collide with inside the same relaxation
 * as shapes, through the same contact response (restitution, friction,
 * events). Worms-, Liero-, Noita-like ground.
 *
 * A terrain copies the mask it is made from (the caller's mask may be
 * changed or destroyed at once); carving and filling change the terrain's
 * own copy. It is placed as tt_mask_place places masks: pixel (px, py)
 * covers x ∈ [origin.x + px·pixel, origin.x + (px+1)·pixel] and
 * y ∈ [origin.y − (py+1)·pixel, origin.y − py·pixel] (rows go down, the
 * world's y goes up). Outside its rectangle a terrain is empty.
 *
 * Contacts read a signed distance to the solid pixels' boundary kept per
 * pixel (the exact distance to the nearest pixel of the other state less
 * half a pixel, clamped to ±band pixels) and sampled bilinearly; the normal
 * is its gradient over two pixels, the distances blurred over 7 × 7 pixels,
 * so a ball rolls down a pixel slope as down a straight one. A particle
 * whose radius is above band − 4 pixels collides as if it were band − 4
 * pixels (the default band, 10, fits radii up to 6 pixels: 0.3 m at
 * 0.05 m): give a terrain band ≥ radius / pixel + 4 for its largest
 * particle. Carves and fills update the bits and the distances around the
 * changed pixels only (the changed box grown by band + 3, read grown by
 * band again): their cost is in proportion to the changed area, not to the
 * terrain's, and the result is what a rebuild would give.
 *
 * A world without terrains pays nothing for them and hashes as before. */
#ifndef TETHER_TERRAIN_H
#define TETHER_TERRAIN_H

#include "mask.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TT_TERRAIN_MAX_BAND 32   ///< most pixels of the distance band
#define TT_MAX_TERRAINS 1024     ///< most live terrains per world

/// How a terrain is made. Start from tt_terrain_def_default().
typedef struct tt_terrain_def {
    const tt_mask *solid;    ///< set pixels are solid ground (copied); required
    tt_vec2 origin;          ///< m, the top-left corner of pixel (0, 0); default (0, 0)
    double pixel;            ///< m per pixel, > 0; default 0.05
    int band;                ///< pixels of distance kept each side of the surface, 5…TT_TERRAIN_MAX_BAND; default 10;
                             ///< radii above band − 4 pixels are seen as band − 4
    double restitution;      ///< bounce, 0…1; default 0
    double friction_static;  ///< μs ≥ 0; default 0.6
    double friction_kinetic; ///< μk ≥ 0; default 0.5
    uint16_t category;       ///< layer bits of the terrain; default 0x0001
    uint16_t mask;           ///< layers it collides with; default 0xFFFF
    uint64_t user;           ///< your data; default 0
} tt_terrain_def;

/// The defaults documented on each tt_terrain_def field.
TT_API tt_terrain_def tt_terrain_def_default(void);
/// Adds a terrain (a copy of def->solid); the null handle on bad input or no memory (tt_last_error says why).
TT_API tt_terrain tt_terrain_create(tt_world *w, const tt_terrain_def *def);
/// Removes a terrain; its handle goes stale.
TT_API tt_result tt_terrain_destroy(tt_world *w, tt_terrain t);
/// True if t names a live terrain of w.
TT_API bool tt_terrain_is_valid(const tt_world *w, tt_terrain t);
/// Live terrains.
TT_API uint32_t tt_world_terrain_count(const tt_world *w);
/// Erases (solid = false) or fills (solid = true) the pixels whose centres lie in the circle (world m).
TT_API tt_result tt_terrain_paint_circle(tt_world *w, tt_terrain t, tt_vec2 centre, double radius, bool solid);
/// Erases (solid = false) or fills the pixels set in m, m's pixel (0, 0) on the terrain's pixel (dx, dy).
TT_API tt_result tt_terrain_paint_mask(tt_world *w, tt_terrain t, const tt_mask *m, int dx, int dy, bool solid);
/// The terrain's own pixels, read only, valid until it is carved, filled or removed (drawing, tests).
TT_API tt_result tt_terrain_get_mask(const tt_world *w, tt_terrain t, const tt_mask **out);
/// Where the terrain lies: origin and pixel size, as tt_mask_place.
TT_API tt_result tt_terrain_get_place(const tt_world *w, tt_terrain t, tt_mask_place *out);
/// Restitution 0…1, μs ≥ 0, μk ≥ 0.
TT_API tt_result tt_terrain_set_material(tt_world *w, tt_terrain t, double restitution, double friction_static,
                                         double friction_kinetic);
TT_API tt_result tt_terrain_get_user(const tt_world *w, tt_terrain t, uint64_t *out);
/// Signed distance (m) from p to the terrain's surface, negative inside, clamped to ±band pixels,
/// and the unit outward normal there (the gradient; (0, 0) where the distance is clamped).
TT_API tt_result tt_terrain_distance(const tt_world *w, tt_terrain t, tt_vec2 p, double *distance, tt_vec2 *normal);
/// Whether world point p lies in a solid pixel.
TT_API tt_result tt_terrain_is_solid(const tt_world *w, tt_terrain t, tt_vec2 p, bool *out);
/// Terrains with a solid pixel meeting the box lo–hi (a point: lo = hi; pixels are closed squares) whose
/// category is in mask, as tt_world_query_point / tt_world_query_aabb list particles and shapes. Writes up
/// to cap (out may be NULL with cap 0); *n gets the full count. Costs the box's pixels / 64 a terrain.
TT_API tt_result tt_world_query_terrains(const tt_world *w, tt_vec2 lo, tt_vec2 hi, uint16_t mask, tt_terrain *out,
                                         uint32_t cap, uint32_t *n);

#ifdef __cplusplus
}
#endif

#endif
