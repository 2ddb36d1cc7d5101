/* tether — pixel masks: w×h bit grids for pixel-perfect sprite collision,
 * built from images, shapes or other masks, and their outlines turned into
 * collision geometry.
 *
 * Coordinates: mask pixel (0, 0) is the image's top-left pixel; x goes
 * right and y goes DOWN, as in the image the mask came from. The world has
 * y going up: tt_mask_place says where a mask sits in the world, and the
 * conversions below (and tt_mask_to_chains) flip y through it.
 *
 * A mask needs no world: every call here but tt_mask_to_chains works on
 * masks alone. Calls that can fail return a tt_result (or NULL) and leave a
 * message in tt_mask_last_error() (one per thread). Overlaps run 64 pixels
 * at a time; results never depend on the processor or the build.
 *
 * Overlap semantics are pygame.mask's: B's pixel (bx, by) lies on A's pixel
 * (bx + dx, by + dy); points are in A's frame; the overlap area is the count
 * of the overlap mask; offsets that put B wholly outside A give no overlap.
 * The "first" overlapping point is the topmost row's leftmost one (pygame
 * returns some overlapping point, in the order of its 64-column strips). */
#ifndef TETHER_MASK_H
#define TETHER_MASK_H

#include "collide.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TT_MASK_MAX_SIDE 16384 ///< largest width or height of a mask, pixels
#define TT_MASK_MAX_OFFSET 1000000000 ///< largest |dx|, |dy| of an offset between masks
#define TT_MASK_MAX_CONVOLVE 1e9 ///< most word operations of one tt_mask_convolve (about a second)

/// A bit mask (opaque). Made by a tt_mask_create… call, freed by tt_mask_destroy.
typedef struct tt_mask tt_mask;

/// A rectangle of pixels: x, y of its top-left pixel, width and height (0 × 0 when empty).
typedef struct tt_mask_rect {
    int x, y, w, h;
} tt_mask_rect;

/// Where a mask lies in the world: the world position of its pixel (0, 0)'s
/// top-left corner, and the side of one pixel in world units (m). World y
/// goes up, so pixel row y lies between origin.y − y·pixel and origin.y − (y+1)·pixel.
typedef struct tt_mask_place {
    tt_vec2 origin;   ///< m; default (0, 0)
    double pixel;     ///< m per pixel, > 0; default 1
} tt_mask_place;

/// A closed outline: points in mask pixel coordinates (corners of pixels:
/// (x, y) is the top-left corner of pixel (x, y)), the last joining the first.
typedef struct tt_mask_polyline {
    tt_vec2 *points;
    uint32_t count;
} tt_mask_polyline;

/// The message of the last failed mask call on this thread ("" if none).
TT_API const char *tt_mask_last_error(void);

/* --- making and freeing --------------------------------------------------- */

/// A w×h mask, every pixel clear (filled false) or set; 1 ≤ w, h ≤ TT_MASK_MAX_SIDE. NULL on failure.
TT_API tt_mask *tt_mask_create(int w, int h, bool filled);
/// Frees a mask; NULL is ignored.
TT_API void tt_mask_destroy(tt_mask *m);
/// A copy of m, or NULL.
TT_API tt_mask *tt_mask_copy(const tt_mask *m);
/// Bytes a w×h mask takes (0 for a bad size): for tt_mask_init, when the caller owns the memory.
TT_API size_t tt_mask_footprint(int w, int h);
/// A w×h mask, every pixel clear, laid out in mem (at least tt_mask_footprint(w, h) bytes, 8-byte aligned). The
/// caller frees mem; never pass the mask to tt_mask_destroy. NULL on bad arguments. (The Lua binding keeps each
/// mask inside its userdata this way, so the collector knows its true size.)
TT_API tt_mask *tt_mask_init(void *mem, size_t size, int w, int h);
/// Copies src's pixels into dst, which must be of the same size.
TT_API tt_result tt_mask_copy_into(tt_mask *dst, const tt_mask *src);
/// A mask of an RGBA image (rows top to bottom, stride bytes apart, ≥ 4·w): a pixel is set when its
/// alpha is > threshold (0…254; pygame's from_surface uses 127).
TT_API tt_mask *tt_mask_from_rgba(const uint8_t *rgba, int w, int h, size_t stride, int threshold);
/// A mask of an RGBA image where a pixel is set when its r, g, b each differ from key's by at most
/// tolerance (0…255) — pygame's from_threshold; with invert, set where it does NOT match (a colour key).
TT_API tt_mask *tt_mask_from_color(const uint8_t *rgba, int w, int h, size_t stride, const uint8_t key[3],
                                   int tolerance, bool invert);
/// A mask from a PNG file's alpha channel (palette, grey, RGB and 16-bit files are converted;
/// files without alpha are opaque everywhere). At most TT_MASK_MAX_SIDE on a side. NULL with a message on
/// an unreadable, truncated or malformed file.
TT_API tt_mask *tt_mask_load_png(const char *path, int threshold);
/// As tt_mask_load_png, from a PNG file's bytes in memory.
TT_API tt_mask *tt_mask_load_png_memory(const void *data, size_t size, int threshold);
/// Writes m as an 8-bit grey+alpha PNG: set pixels white and opaque, clear ones transparent.
TT_API tt_result tt_mask_save_png(const tt_mask *m, const char *path);
/// A copy of m turned by angle radians counter-clockwise as seen on screen (nearest pixel, about its
/// centre), in a new mask just large enough to hold it; |angle| ≤ 1e6.
TT_API tt_mask *tt_mask_rotated(const tt_mask *m, double angle);
/// A copy of m scaled to w×h pixels (nearest pixel).
TT_API tt_mask *tt_mask_scaled(const tt_mask *m, int w, int h);

/* --- pixels ---------------------------------------------------------------- */

/// Width and height; either pointer may be NULL. TT_EINVAL when m is NULL.
TT_API tt_result tt_mask_size(const tt_mask *m, int *w, int *h);
/// 1 if pixel (x, y) is set, 0 if clear, −1 (with a message) when m is NULL or (x, y) is outside.
TT_API int tt_mask_get(const tt_mask *m, int x, int y);
/// Sets (value true) or clears pixel (x, y), which must be inside.
TT_API tt_result tt_mask_set(tt_mask *m, int x, int y, bool value);
/// Number of set pixels (0 when m is NULL).
TT_API int64_t tt_mask_count(const tt_mask *m);
/// Clears every pixel, sets every pixel, or flips every pixel.
TT_API tt_result tt_mask_clear(tt_mask *m);
TT_API tt_result tt_mask_fill(tt_mask *m);
TT_API tt_result tt_mask_invert(tt_mask *m);
/// The smallest rectangle holding every set pixel (w = h = 0 when none is set).
TT_API tt_result tt_mask_bounding_rect(const tt_mask *m, tt_mask_rect *out);
/// Mean of the set pixels' (x, y) indices, (0, 0) when none is set (pygame's centroid, unrounded).
TT_API tt_result tt_mask_centroid(const tt_mask *m, tt_vec2 *out);
/// ORs src into dst with src's pixel (0, 0) on dst's (dx, dy); what falls outside dst is dropped.
TT_API tt_result tt_mask_draw(tt_mask *dst, const tt_mask *src, int dx, int dy);
/// Clears in dst every pixel set in src placed as for tt_mask_draw (AND NOT).
TT_API tt_result tt_mask_erase(tt_mask *dst, const tt_mask *src, int dx, int dy);
/// Sets (value true) or clears the pixels whose centres lie in the circle of centre (cx, cy) and radius r
/// (pixel units, |values| ≤ 1e6), the rectangle, or the polygon of n (3…1e6) points (even-odd rule).
TT_API tt_result tt_mask_fill_circle(tt_mask *m, double cx, double cy, double r, bool value);
TT_API tt_result tt_mask_fill_rect(tt_mask *m, int x, int y, int w, int h, bool value);
TT_API tt_result tt_mask_fill_polygon(tt_mask *m, const tt_vec2 *points, uint32_t n, bool value);

/* --- overlap of B placed at (dx, dy) on A ----------------------------------- */

/// Whether they overlap; when they do and x, y are not NULL, the first overlapping pixel in A's frame.
TT_API bool tt_mask_overlap(const tt_mask *a, const tt_mask *b, int dx, int dy, int *x, int *y);
/// Number of overlapping pixels (−1 with a message on bad arguments).
TT_API int64_t tt_mask_overlap_area(const tt_mask *a, const tt_mask *b, int dx, int dy);
/// A new mask of A's size holding the overlapping pixels, or NULL.
TT_API tt_mask *tt_mask_overlap_mask(const tt_mask *a, const tt_mask *b, int dx, int dy);
/// The same into out, a mask of A's size (every pixel of it written; out may not be A or B).
TT_API tt_result tt_mask_overlap_mask_into(tt_mask *out, const tt_mask *a, const tt_mask *b, int dx, int dy);
/// The direction to push B out of A, in A's image frame (y down), from the overlap area's gradient
/// (area at dx ± 1 and dy ± 1, as pygame's examples do): a unit vector, or (0, 0) when they do not
/// overlap or the gradient is flat.
TT_API tt_result tt_mask_overlap_normal(const tt_mask *a, const tt_mask *b, int dx, int dy, tt_vec2 *out);
/// pygame's convolve: a new (wa + wb − 1) × (ha + hb − 1) mask whose pixel (x, y) is set when B placed at
/// (x − wb + 1, y − hb + 1) overlaps A; where that pixel is clear, B fits. It costs count(B) × ha × (wa/64 + 1)
/// word operations; over TT_MASK_MAX_CONVOLVE it is refused (NULL).
TT_API tt_mask *tt_mask_convolve(const tt_mask *a, const tt_mask *b);

/* --- shape of the set pixels --------------------------------------------- */

/// Number of 8-connected components of set pixels.
TT_API int64_t tt_mask_component_count(const tt_mask *m);
/// A new mask holding only the component containing pixel (x, y) (empty if that pixel is clear), or the
/// largest component (the first in row order among equals) when x is −1 and y is −1.
TT_API tt_mask *tt_mask_component(const tt_mask *m, int x, int y);
/// Bounding rects of each 8-connected component, in the order of their first pixel (row by row) into
/// out[0..cap); *count gets how many there are (out may be NULL with cap 0 to count).
TT_API tt_result tt_mask_component_rects(const tt_mask *m, tt_mask_rect *out, uint32_t cap, uint32_t *count);
/// The border pixels of the first component (row order) in order around it, 8-connected, as pygame's
/// outline(): points (x, y) into out[0..cap) as pairs, *count points in all.
TT_API tt_result tt_mask_outline(const tt_mask *m, int *xy, uint32_t cap, uint32_t *count);
/// Marching squares: every boundary between set and clear pixels as closed polylines through pixel corners
/// and edge midpoints, simplified by Douglas-Peucker to within tolerance pixels (0 … 1e6; 0 keeps every
/// turn). Outer boundaries run counter-clockwise on screen, holes clockwise. *lines (free with
/// tt_mask_polylines_free) gets *count polylines.
TT_API tt_result tt_mask_polylines(const tt_mask *m, double tolerance, tt_mask_polyline **lines, uint32_t *count);
TT_API void tt_mask_polylines_free(tt_mask_polyline *lines, uint32_t count);

/* --- masks in the world ---------------------------------------------------- */

/// The default place: origin (0, 0), one world unit per pixel.
TT_API tt_mask_place tt_mask_place_default(void);
/// World position of the point at mask pixel coordinates p (pixel corners are integers, y down).
TT_API tt_vec2 tt_mask_to_world(const tt_mask_place *place, tt_vec2 p);
/// Mask pixel coordinates of world point q (the pixel holding q is (floor x, floor y)).
TT_API tt_vec2 tt_mask_from_world(const tt_mask_place *place, tt_vec2 q);
/// The mask's outline (tt_mask_polylines at tolerance pixels) as static looped chain shapes of w placed by
/// place, with the material, layers and flags of def (NULL: tt_shape_def_default(); its type, position,
/// angle and points are ignored); shape handles into out[0..cap), *count of them. A failing call
/// (bad arguments, more polylines than cap) creates nothing; the reason is in tt_mask_last_error().
TT_API tt_result tt_mask_to_chains(const tt_mask *m, tt_world *w, const tt_mask_place *place, double tolerance,
                                   const tt_shape_def *def, tt_shape *out, uint32_t cap, uint32_t *count);

#ifdef __cplusplus
}
#endif

#endif
