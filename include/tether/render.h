/* tether — drawing: a canvas that batches circles, lines, polygons, text and
 * images (plain C, no GL), a debug draw of a world onto it, and two GL back
 * ends that show a canvas: headless (OSMesa, PNG files) and a window (SDL2).
 *
 * This header is public but NOT part of tether.h: it belongs to the separate
 * library libtether_render.a (link it with `pkg-config --libs osmesa sdl2
 * libpng`), so a program that only simulates never links GL, SDL or libpng.
 *
 * Coordinates: the world layer is in world units (m, y up) seen through the
 * canvas camera; the screen layer is in pixels, origin top-left, y down
 * (for a HUD). Every frame: tt_canvas_clear, draw, then hand the canvas to a
 * back end. Draw calls only append to per-kind vertex arrays; a back end
 * sends each array with one GL draw call, so the cost of 100 000 circles is
 * one array, not 100 000 calls. Order inside a layer is by kind: images,
 * then lines and polygons, then circles, then text; the screen layer is
 * drawn after the world layer. */
#ifndef TETHER_RENDER_H
#define TETHER_RENDER_H

#include "tether.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A colour, 8 bits per channel, straight (not premultiplied) alpha.
typedef struct tt_color {
    uint8_t r, g, b, a;
} tt_color;

/// A batch of drawing for one frame (no GL inside). Owned by the caller.
typedef struct tt_canvas tt_canvas;

/// An RGBA image (8 bits per channel, rows top to bottom) that a canvas can
/// draw; the GL back ends upload it as a texture once, and again after
/// tt_image_touch.
typedef struct tt_image tt_image;

/// Canvas layers.
typedef enum tt_layer {
    TT_LAYER_WORLD = 0, ///< world units through the camera; the default
    TT_LAYER_SCREEN     ///< pixels, origin top-left, y down: for a HUD
} tt_layer;

/// What tt_canvas_draw_world draws. Start from tt_debug_draw_default().
typedef struct tt_debug_draw {
    bool particles;        ///< default true
    bool springs;          ///< default true; coloured by strain (blue compressed, grey at rest, red stretched)
    bool constraints;      ///< default true; distance constraints and pins as lines
    bool shapes;           ///< default true; static and kinematic shapes as outlines (sensors dimmer)
    double min_radius_px;  ///< particles smaller than this on screen are drawn this big, px; default 1.5
    double strain_full;    ///< |length − rest| / rest that gets the full stress colour; default 0.1
    tt_color particle;     ///< default (235, 200, 90, 255)
    tt_color pinned;       ///< default (230, 70, 70, 255)
    tt_color constraint;   ///< default (120, 190, 230, 255)
    tt_color shape;        ///< default (150, 220, 150, 255)
    double alpha;          ///< where between the last two steps particles and springs are drawn, 0…1: previous +
                           ///< alpha·(current − previous) (tt_world_read_previous_positions; pass tt_clock_alpha);
                           ///< default 1, the current positions. Constraint lines and shapes are drawn as they are now
} tt_debug_draw;

/// Makes a canvas of width × height pixels (1…16384 each); NULL if out of memory or out of range.
TT_API tt_canvas *tt_canvas_create(int width, int height);
/// Frees a canvas. NULL is allowed.
TT_API void tt_canvas_destroy(tt_canvas *c);
/// The message of the last failed call on c ("" when none).
TT_API const char *tt_canvas_error(const tt_canvas *c);
/// Changes the size in pixels (1…16384 each); the camera keeps its centre and zoom.
TT_API tt_result tt_canvas_resize(tt_canvas *c, int width, int height);
/// Size in pixels.
TT_API void tt_canvas_size(const tt_canvas *c, int *width, int *height);
/// Starts a frame: empties every batch and sets the background colour. Keeps camera, colour, layer, line width.
TT_API void tt_canvas_clear(tt_canvas *c, tt_color background);
/// Camera: the world point at the centre of the canvas, and the zoom in
/// pixels per world unit (1e-9 … 1e9). Default centre (0, 0), zoom 30.
TT_API tt_result tt_canvas_set_camera(tt_canvas *c, tt_vec2 center, double zoom);
TT_API void tt_canvas_get_camera(const tt_canvas *c, tt_vec2 *center, double *zoom);
/// Sets the camera so the world rectangle [lo, hi] fits inside the canvas with `margin_px` around it.
TT_API tt_result tt_canvas_fit(tt_canvas *c, tt_vec2 lo, tt_vec2 hi, double margin_px);
/// World point → pixel (origin top-left, y down), and back.
TT_API tt_vec2 tt_canvas_to_pixels(const tt_canvas *c, tt_vec2 world);
TT_API tt_vec2 tt_canvas_to_world(const tt_canvas *c, tt_vec2 pixels);
/// Colour of the next draws; default white.
TT_API void tt_canvas_set_color(tt_canvas *c, tt_color color);
TT_API tt_color tt_canvas_get_color(const tt_canvas *c);
/// Layer of the next draws (TT_LAYER_WORLD or TT_LAYER_SCREEN).
TT_API tt_result tt_canvas_set_layer(tt_canvas *c, tt_layer layer);
TT_API tt_layer tt_canvas_get_layer(const tt_canvas *c);
/// Width of lines and outlines, px (0.1…1000); default 1.5.
TT_API tt_result tt_canvas_set_line_width(tt_canvas *c, double px);
/// A circle (radius in the layer's units, ≥ 0), filled or outlined; anti-aliased. Circles entirely off the canvas are culled.
TT_API tt_result tt_canvas_circle(tt_canvas *c, tt_vec2 center, double radius, bool filled);
/// A straight line of the current line width.
TT_API tt_result tt_canvas_line(tt_canvas *c, tt_vec2 a, tt_vec2 b);
/// A line whose two ends have their own colours (stress gradients).
TT_API tt_result tt_canvas_line2(tt_canvas *c, tt_vec2 a, tt_vec2 b, tt_color ca, tt_color cb);
/// A polygon of 3…1 000 000 points, filled or outlined. Filled: either winding; concave is fine up to
/// 256 points; longer outlines and self-crossing ones are drawn as a fan from the first point.
TT_API tt_result tt_canvas_polygon(tt_canvas *c, const tt_vec2 *points, int n, bool filled);
/// Text in the built-in 5×7 font (ASCII 32…126; others show as '?'), top-left
/// corner at pos, each font pixel `scale` screen pixels (1…64). '\n' starts a new line.
TT_API tt_result tt_canvas_text(tt_canvas *c, tt_vec2 pos, const char *text, int scale);
/// Width and height in pixels that tt_canvas_text would cover.
TT_API void tt_canvas_text_size(const char *text, int scale, int *width, int *height);
/// An image stretched over the axis-aligned rectangle from `lo` to `hi` (layer units), tinted by the current colour.
TT_API tt_result tt_canvas_image(tt_canvas *c, tt_image *img, tt_vec2 lo, tt_vec2 hi);
/// Primitives recorded since the last clear (circles, line/polygon triangles, text quads, images).
TT_API size_t tt_canvas_primitive_count(const tt_canvas *c);

/// The defaults documented on each tt_debug_draw field.
TT_API tt_debug_draw tt_debug_draw_default(void);
/// Debug draw of everything a world holds that the public API can read:
/// springs, then particles (pinned ones in their own colour), on the world
/// layer. opts may be NULL for the defaults.
TT_API tt_result tt_canvas_draw_world(tt_canvas *c, const tt_world *w, const tt_debug_draw *opts);

/// A new image, width × height (1…16384 each), transparent black; NULL if out of memory.
TT_API tt_image *tt_image_create(int width, int height);
/// Reads a PNG file (any colour type, converted to RGBA); NULL with a message in err on failure.
TT_API tt_image *tt_image_load_png(const char *path, char *err, size_t err_size);
/// Frees an image; one a canvas recorded since its last clear stays until
/// that canvas (the last that holds it) is cleared or destroyed, so the frame
/// being recorded still draws it.
TT_API void tt_image_destroy(tt_image *img);
TT_API void tt_image_size(const tt_image *img, int *width, int *height);
/// The pixels, RGBA, rows top to bottom, width·4 bytes per row. Call tt_image_touch after changing them.
TT_API uint8_t *tt_image_pixels(tt_image *img);
/// Marks the pixels changed: back ends upload them again before the next draw.
TT_API void tt_image_touch(tt_image *img);
/// An image of a mask's size: colour on where a pixel is set, off where clear (mask pixel (0, 0) is the
/// image's top-left). Drawn with tt_canvas_image, it shows the mask; NULL when m is NULL or memory runs out.
TT_API tt_image *tt_image_from_mask(const tt_mask *m, tt_color on, tt_color off);
/// Repaints img (of the mask's size, TT_EINVAL otherwise) from m as tt_image_from_mask does, and touches it.
TT_API tt_result tt_image_paint_mask(tt_image *img, const tt_mask *m, tt_color on, tt_color off);

/// Writes RGBA pixels (stride bytes per row; bottom_up when row 0 is the
/// bottom, as GL reads them) to a PNG file. TT_EINVAL with a message in err on failure.
TT_API tt_result tt_png_write(const char *path, const uint8_t *rgba, int width, int height, size_t stride,
                              bool bottom_up, char *err, size_t err_size);

/// Headless back end: an off-screen OpenGL context (OSMesa, software).
typedef struct tt_headless tt_headless;
/// A context of width × height pixels (1…16384); NULL with a message in err on failure.
TT_API tt_headless *tt_headless_create(int width, int height, char *err, size_t err_size);
TT_API void tt_headless_destroy(tt_headless *h);
/// Draws the canvas (its size must equal the context's) and waits for it.
TT_API tt_result tt_headless_render(tt_headless *h, const tt_canvas *c);
/// The frame just rendered: RGBA, rows bottom to top, width·4 bytes per row.
TT_API const uint8_t *tt_headless_pixels(const tt_headless *h, int *width, int *height);
/// Writes the frame just rendered to a PNG file.
TT_API tt_result tt_headless_write_png(tt_headless *h, const char *path);
/// The message of the last failed call on h.
TT_API const char *tt_headless_error(const tt_headless *h);
/// GL draw calls the last render made: one per layer and kind in use (images: one each).
TT_API unsigned tt_headless_draw_calls(const tt_headless *h);

/// Windowed back end: an SDL2 window with an OpenGL context. Events are the
/// caller's (SDL_PollEvent); this only opens, draws, reads back and closes.
typedef struct tt_window tt_window;
/// Opens a resizable window; NULL with a message in err on failure (no display, no GL).
TT_API tt_window *tt_window_open(const char *title, int width, int height, char *err, size_t err_size);
TT_API void tt_window_close(tt_window *win);
/// Size of the drawable area in pixels (follows resizes).
TT_API void tt_window_size(const tt_window *win, int *width, int *height);
/// Draws the canvas into the back buffer; when screenshot is not NULL also
/// writes it to that PNG file; then shows it.
TT_API tt_result tt_window_present(tt_window *win, const tt_canvas *c, const char *screenshot);
TT_API const char *tt_window_error(const tt_window *win);
/// GL draw calls the last present made (see tt_headless_draw_calls).
TT_API unsigned tt_window_draw_calls(const tt_window *win);

#ifdef __cplusplus
}
#endif

#endif
