/* tether — the GL drawing shared by the headless and the windowed back ends.
 *
 * GL 2.1 with three small GLSL 1.20 programs (solid triangles, anti-aliased
 * circles on quads, textured quads). Per layer and kind, one buffer upload
 * and one draw call: images, triangles (lines, polygons), circles, text.
 * Every entry point is loaded through the back end's getproc, never linked:
 * libOSMesa and libGL both export gl* symbols, and a direct call would go to
 * whichever the linker saw first. */
#include "render_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdlib.h>
#include <string.h>

#ifndef APIENTRY
#define APIENTRY
#endif

#define GL_FUNCS(X)                                                                                  \
    X(void, Viewport, (GLint, GLint, GLsizei, GLsizei))                                              \
    X(void, ClearColor, (GLfloat, GLfloat, GLfloat, GLfloat))                                        \
    X(void, Clear, (GLbitfield))                                                                     \
    X(void, Enable, (GLenum))                                                                        \
    X(void, Disable, (GLenum))                                                                       \
    X(void, BlendFuncSeparate, (GLenum, GLenum, GLenum, GLenum))                                     \
    X(void, GenBuffers, (GLsizei, GLuint *))                                                         \
    X(void, DeleteBuffers, (GLsizei, const GLuint *))                                                \
    X(void, BindBuffer, (GLenum, GLuint))                                                            \
    X(void, BufferData, (GLenum, GLsizeiptr, const void *, GLenum))                                  \
    X(GLuint, CreateShader, (GLenum))                                                                \
    X(void, ShaderSource, (GLuint, GLsizei, const GLchar *const *, const GLint *))                   \
    X(void, CompileShader, (GLuint))                                                                 \
    X(void, GetShaderiv, (GLuint, GLenum, GLint *))                                                  \
    X(void, GetShaderInfoLog, (GLuint, GLsizei, GLsizei *, GLchar *))                                \
    X(void, DeleteShader, (GLuint))                                                                  \
    X(GLuint, CreateProgram, (void))                                                                 \
    X(void, AttachShader, (GLuint, GLuint))                                                          \
    X(void, BindAttribLocation, (GLuint, GLuint, const GLchar *))                                    \
    X(void, LinkProgram, (GLuint))                                                                   \
    X(void, GetProgramiv, (GLuint, GLenum, GLint *))                                                 \
    X(void, GetProgramInfoLog, (GLuint, GLsizei, GLsizei *, GLchar *))                               \
    X(void, DeleteProgram, (GLuint))                                                                 \
    X(void, UseProgram, (GLuint))                                                                    \
    X(GLint, GetUniformLocation, (GLuint, const GLchar *))                                           \
    X(void, Uniform2f, (GLint, GLfloat, GLfloat))                                                    \
    X(void, Uniform1i, (GLint, GLint))                                                               \
    X(void, EnableVertexAttribArray, (GLuint))                                                       \
    X(void, DisableVertexAttribArray, (GLuint))                                                      \
    X(void, VertexAttribPointer, (GLuint, GLint, GLenum, GLboolean, GLsizei, const void *))          \
    X(void, DrawArrays, (GLenum, GLint, GLsizei))                                                    \
    X(void, DrawElements, (GLenum, GLsizei, GLenum, const void *))                                   \
    X(void, GenTextures, (GLsizei, GLuint *))                                                        \
    X(void, DeleteTextures, (GLsizei, const GLuint *))                                               \
    X(void, BindTexture, (GLenum, GLuint))                                                           \
    X(void, ActiveTexture, (GLenum))                                                                 \
    X(void, TexImage2D, (GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void *)) \
    X(void, TexParameteri, (GLenum, GLenum, GLint))                                                  \
    X(void, PixelStorei, (GLenum, GLint))                                                            \
    X(void, ReadPixels, (GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *))                    \
    X(void, Finish, (void))                                                                          \
    X(GLenum, GetError, (void))                                                                      \
    X(void, GetFloatv, (GLenum, GLfloat *))

typedef struct texslot {
    uint64_t image_id;
    uint32_t version;
    GLuint tex;
    uint64_t last_frame;
} texslot;

struct tt__gl {
#define X(ret, name, args) ret(APIENTRY *name) args;
    GL_FUNCS(X)
#undef X
    GLuint prog_solid, prog_circle, prog_tex, prog_point;
    GLint size_solid, size_circle, size_tex, sampler, size_point;
    float max_point;      /* largest point sprite, px */
    GLuint vbo, ibo;
    size_t quads_indexed; /* quads the index buffer covers */
    texslot *tex;
    size_t ntex, captex;
    uint64_t frame;
    unsigned draw_calls;  /* glDraw* calls of the last frame */
};

enum { A_POS = 0, A_COLOR = 1, A_LOCAL = 2, A_RADIUS = 3, A_UV = 4 };

static const char *vs_solid =
    "#version 120\n"
    "attribute vec2 a_pos; attribute vec4 a_color; uniform vec2 u_size; varying vec4 v_color;\n"
    "void main() { v_color = a_color;\n"
    "  gl_Position = vec4(a_pos.x / u_size.x * 2.0 - 1.0, 1.0 - a_pos.y / u_size.y * 2.0, 0.0, 1.0); }\n";
static const char *fs_solid =
    "#version 120\n"
    "varying vec4 v_color; void main() { gl_FragColor = v_color; }\n";
static const char *vs_circle =
    "#version 120\n"
    "attribute vec2 a_pos; attribute vec4 a_color; attribute vec2 a_local; attribute vec2 a_radius;\n"
    "uniform vec2 u_size; varying vec4 v_color; varying vec2 v_local; varying vec2 v_radius;\n"
    "void main() { v_color = a_color; v_local = a_local; v_radius = a_radius;\n"
    "  gl_Position = vec4(a_pos.x / u_size.x * 2.0 - 1.0, 1.0 - a_pos.y / u_size.y * 2.0, 0.0, 1.0); }\n";
static const char *fs_circle =
    "#version 120\n"
    "varying vec4 v_color; varying vec2 v_local; varying vec2 v_radius;\n"
    "void main() { float d = length(v_local);\n"
    "  float a = clamp(v_radius.x - d + 0.5, 0.0, 1.0);\n"
    "  if (v_radius.y >= 0.0) a *= clamp(d - v_radius.y + 0.5, 0.0, 1.0);\n"
    "  if (a <= 0.0) discard;\n"
    "  gl_FragColor = vec4(v_color.rgb, v_color.a * a); }\n";
/* small circles as point sprites: one vertex, the quad made by the rasteriser */
static const char *vs_point =
    "#version 120\n"
    "attribute vec2 a_pos; attribute vec4 a_color; attribute vec2 a_radius; uniform vec2 u_size;\n"
    "varying vec4 v_color; varying vec4 v_disc; /* centre (window coordinates, y up), radius, inner radius */\n"
    "void main() { v_color = a_color; gl_PointSize = 2.0 * a_radius.x + 1.0;\n"
    "  v_disc = vec4(a_pos.x, u_size.y - a_pos.y, a_radius);\n"
    "  gl_Position = vec4(a_pos.x / u_size.x * 2.0 - 1.0, 1.0 - a_pos.y / u_size.y * 2.0, 0.0, 1.0); }\n";
static const char *fs_point =
    "#version 120\n"
    "varying vec4 v_color; varying vec4 v_disc;\n"
    "void main() { float d = length(gl_FragCoord.xy - v_disc.xy);\n"
    "  float a = clamp(v_disc.z - d + 0.5, 0.0, 1.0);\n"
    "  if (v_disc.w >= 0.0) a *= clamp(d - v_disc.w + 0.5, 0.0, 1.0);\n"
    "  if (a <= 0.0) discard;\n"
    "  gl_FragColor = vec4(v_color.rgb, v_color.a * a); }\n";
static const char *vs_tex =
    "#version 120\n"
    "attribute vec2 a_pos; attribute vec4 a_color; attribute vec2 a_uv; uniform vec2 u_size;\n"
    "varying vec4 v_color; varying vec2 v_uv;\n"
    "void main() { v_color = a_color; v_uv = a_uv;\n"
    "  gl_Position = vec4(a_pos.x / u_size.x * 2.0 - 1.0, 1.0 - a_pos.y / u_size.y * 2.0, 0.0, 1.0); }\n";
static const char *fs_tex =
    "#version 120\n"
    "uniform sampler2D u_tex; varying vec4 v_color; varying vec2 v_uv;\n"
    "void main() { gl_FragColor = texture2D(u_tex, v_uv) * v_color; }\n";

static GLuint compile(tt__gl *g, GLenum kind, const char *src, char *err, size_t n)
{
    GLuint s = g->CreateShader(kind);
    g->ShaderSource(s, 1, &src, NULL);
    g->CompileShader(s);
    GLint ok = 0;
    g->GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        g->GetShaderInfoLog(s, sizeof log, NULL, log);
        tt__errf(err, n, "GL shader does not compile: %s", log);
        g->DeleteShader(s);
        return 0;
    }
    return s;
}

static GLuint program(tt__gl *g, const char *vs, const char *fs, char *err, size_t n)
{
    GLuint v = compile(g, GL_VERTEX_SHADER, vs, err, n);
    if (!v) return 0;
    GLuint f = compile(g, GL_FRAGMENT_SHADER, fs, err, n);
    if (!f) { g->DeleteShader(v); return 0; }
    GLuint p = g->CreateProgram();
    g->AttachShader(p, v);
    g->AttachShader(p, f);
    g->BindAttribLocation(p, A_POS, "a_pos");
    g->BindAttribLocation(p, A_COLOR, "a_color");
    g->BindAttribLocation(p, A_LOCAL, "a_local");
    g->BindAttribLocation(p, A_RADIUS, "a_radius");
    g->BindAttribLocation(p, A_UV, "a_uv");
    g->LinkProgram(p);
    g->DeleteShader(v);
    g->DeleteShader(f);
    GLint ok = 0;
    g->GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        g->GetProgramInfoLog(p, sizeof log, NULL, log);
        tt__errf(err, n, "GL program does not link: %s", log);
        g->DeleteProgram(p);
        return 0;
    }
    return p;
}

tt__gl *tt__gl_create(void *(*getproc)(const char *name), char *err, size_t n)
{
    tt__gl *g = calloc(1, sizeof *g);
    if (!g) { tt__errf(err, n, "out of memory"); return NULL; }
    void *fp;
#define X(ret, name, args)                                                              \
    fp = getproc("gl" #name);                                                           \
    if (!fp) { tt__errf(err, n, "OpenGL function gl%s is missing (need GL 2.1)", #name); free(g); return NULL; } \
    memcpy(&g->name, &fp, sizeof fp);
    GL_FUNCS(X)
#undef X
    g->prog_solid = program(g, vs_solid, fs_solid, err, n);
    g->prog_circle = g->prog_solid ? program(g, vs_circle, fs_circle, err, n) : 0;
    g->prog_tex = g->prog_circle ? program(g, vs_tex, fs_tex, err, n) : 0;
    g->prog_point = g->prog_tex ? program(g, vs_point, fs_point, err, n) : 0;
    if (!g->prog_point) { tt__gl_destroy(g); return NULL; }
    g->size_point = g->GetUniformLocation(g->prog_point, "u_size");
    GLfloat range[2] = {1, 1};
    g->GetFloatv(GL_ALIASED_POINT_SIZE_RANGE, range);
    g->max_point = range[1];
    g->size_solid = g->GetUniformLocation(g->prog_solid, "u_size");
    g->size_circle = g->GetUniformLocation(g->prog_circle, "u_size");
    g->size_tex = g->GetUniformLocation(g->prog_tex, "u_size");
    g->sampler = g->GetUniformLocation(g->prog_tex, "u_tex");
    g->GenBuffers(1, &g->vbo);
    g->GenBuffers(1, &g->ibo);
    return g;
}

void tt__gl_destroy(tt__gl *g)
{
    if (!g) return;
    if (g->DeleteProgram) {
        if (g->prog_solid) g->DeleteProgram(g->prog_solid);
        if (g->prog_circle) g->DeleteProgram(g->prog_circle);
        if (g->prog_tex) g->DeleteProgram(g->prog_tex);
        if (g->prog_point) g->DeleteProgram(g->prog_point);
        if (g->vbo) g->DeleteBuffers(1, &g->vbo);
        if (g->ibo) g->DeleteBuffers(1, &g->ibo);
        for (size_t i = 0; i < g->ntex; i++) g->DeleteTextures(1, &g->tex[i].tex);
    }
    free(g->tex);
    free(g);
}

static void draw_solid(tt__gl *g, const tt__solid_array *a, int w, int h)
{
    if (a->n == 0) return;
    g->UseProgram(g->prog_solid);
    g->Uniform2f(g->size_solid, (float)w, (float)h);
    g->BindBuffer(GL_ARRAY_BUFFER, g->vbo);
    g->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(a->n * sizeof *a->v), a->v, GL_STREAM_DRAW);
    g->EnableVertexAttribArray(A_POS);
    g->EnableVertexAttribArray(A_COLOR);
    g->VertexAttribPointer(A_POS, 2, GL_FLOAT, GL_FALSE, sizeof(tt__vsolid), (void *)offsetof(tt__vsolid, x));
    g->VertexAttribPointer(A_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(tt__vsolid), (void *)offsetof(tt__vsolid, rgba));
    g->DrawArrays(GL_TRIANGLES, 0, (GLsizei)a->n);
    g->draw_calls++;
    g->DisableVertexAttribArray(A_POS);
    g->DisableVertexAttribArray(A_COLOR);
}

/* Index buffer 0 1 2 0 2 3, 4 5 6 4 6 7, …: quads as triangles. */
static bool quad_indices(tt__gl *g, size_t quads)
{
    if (quads <= g->quads_indexed) return true;
    size_t nq = g->quads_indexed ? g->quads_indexed : 4096;
    while (nq < quads) nq *= 2;
    uint32_t *idx = malloc(nq * 6 * sizeof *idx);
    if (!idx) return false;
    for (size_t q = 0; q < nq; q++) {
        uint32_t b = (uint32_t)(q * 4);
        uint32_t *p = idx + q * 6;
        p[0] = b; p[1] = b + 1; p[2] = b + 2; p[3] = b; p[4] = b + 2; p[5] = b + 3;
    }
    g->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->ibo);
    g->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(nq * 6 * sizeof *idx), idx, GL_STATIC_DRAW);
    free(idx);
    g->quads_indexed = nq;
    return true;
}

static bool draw_circles(tt__gl *g, const tt__circle_array *a, int w, int h)
{
    if (a->n == 0) return true;
    size_t quads = a->n / 4;
    if (!quad_indices(g, quads)) return false;
    g->UseProgram(g->prog_circle);
    g->Uniform2f(g->size_circle, (float)w, (float)h);
    g->BindBuffer(GL_ARRAY_BUFFER, g->vbo);
    g->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(a->n * sizeof *a->v), a->v, GL_STREAM_DRAW);
    g->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->ibo);
    g->EnableVertexAttribArray(A_POS);
    g->EnableVertexAttribArray(A_COLOR);
    g->EnableVertexAttribArray(A_LOCAL);
    g->EnableVertexAttribArray(A_RADIUS);
    size_t st = sizeof(tt__vcircle);
    g->VertexAttribPointer(A_POS, 2, GL_FLOAT, GL_FALSE, (GLsizei)st, (void *)offsetof(tt__vcircle, x));
    g->VertexAttribPointer(A_LOCAL, 2, GL_FLOAT, GL_FALSE, (GLsizei)st, (void *)offsetof(tt__vcircle, lx));
    g->VertexAttribPointer(A_RADIUS, 2, GL_FLOAT, GL_FALSE, (GLsizei)st, (void *)offsetof(tt__vcircle, r));
    g->VertexAttribPointer(A_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE, (GLsizei)st, (void *)offsetof(tt__vcircle, rgba));
    g->DrawElements(GL_TRIANGLES, (GLsizei)(quads * 6), GL_UNSIGNED_INT, NULL);
    g->draw_calls++;
    g->DisableVertexAttribArray(A_POS);
    g->DisableVertexAttribArray(A_COLOR);
    g->DisableVertexAttribArray(A_LOCAL);
    g->DisableVertexAttribArray(A_RADIUS);
    g->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    return true;
}

static bool draw_circles(tt__gl *g, const tt__circle_array *a, int w, int h);

/* Where points cannot be as large as TT__POINT_MAX_RADIUS needs, they are drawn as quads. */
static bool points_as_quads(tt__gl *g, const tt__point_array *a, int w, int h)
{
    tt__circle_array q = {malloc(a->n * 4 * sizeof(tt__vcircle)), a->n * 4, a->n * 4};
    if (!q.v) return false;
    static const float sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    for (size_t i = 0; i < a->n; i++) {
        const tt__vpoint *p = &a->v[i];
        float e = p->r + 0.5f;
        for (int k = 0; k < 4; k++) {
            tt__vcircle *v = &q.v[4 * i + k];
            v->x = p->x + sx[k] * e;
            v->y = p->y + sy[k] * e;
            v->lx = sx[k] * e;
            v->ly = sy[k] * e;
            v->r = p->r;
            v->inner = p->inner;
            memcpy(v->rgba, p->rgba, 4);
        }
    }
    bool ok = draw_circles(g, &q, w, h);
    free(q.v);
    return ok;
}

static bool draw_points(tt__gl *g, const tt__point_array *a, int w, int h)
{
    if (a->n == 0) return true;
    if (g->max_point < 2.0f * TT__POINT_MAX_RADIUS + 1.0f) return points_as_quads(g, a, w, h);
    g->UseProgram(g->prog_point);
    g->Uniform2f(g->size_point, (float)w, (float)h);
    g->BindBuffer(GL_ARRAY_BUFFER, g->vbo);
    g->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(a->n * sizeof *a->v), a->v, GL_STREAM_DRAW);
    g->EnableVertexAttribArray(A_POS);
    g->EnableVertexAttribArray(A_COLOR);
    g->EnableVertexAttribArray(A_RADIUS);
    size_t st = sizeof(tt__vpoint);
    g->VertexAttribPointer(A_POS, 2, GL_FLOAT, GL_FALSE, (GLsizei)st, (void *)offsetof(tt__vpoint, x));
    g->VertexAttribPointer(A_RADIUS, 2, GL_FLOAT, GL_FALSE, (GLsizei)st, (void *)offsetof(tt__vpoint, r));
    g->VertexAttribPointer(A_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE, (GLsizei)st, (void *)offsetof(tt__vpoint, rgba));
    g->DrawArrays(GL_POINTS, 0, (GLsizei)a->n);
    g->draw_calls++;
    g->DisableVertexAttribArray(A_POS);
    g->DisableVertexAttribArray(A_COLOR);
    g->DisableVertexAttribArray(A_RADIUS);
    return true;
}

/* The texture of img, uploaded when new or touched. */
static GLuint texture_of(tt__gl *g, tt_image *img)
{
    texslot *t = NULL;
    for (size_t i = 0; i < g->ntex; i++)
        if (g->tex[i].image_id == img->id) { t = &g->tex[i]; break; }
    if (!t) {
        if (g->ntex == g->captex) {
            size_t nc = g->captex ? g->captex * 2 : 8;
            texslot *p = realloc(g->tex, nc * sizeof *p);
            if (!p) return 0;
            g->tex = p;
            g->captex = nc;
        }
        t = &g->tex[g->ntex++];
        t->image_id = img->id;
        t->version = img->version - 1; /* forces the upload */
        g->GenTextures(1, &t->tex);
        g->BindTexture(GL_TEXTURE_2D, t->tex);
        g->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        g->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        g->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        g->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    g->BindTexture(GL_TEXTURE_2D, t->tex);
    if (t->version != img->version) {
        g->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        g->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, img->width, img->height, 0, GL_RGBA, GL_UNSIGNED_BYTE, img->rgba);
        t->version = img->version;
    }
    t->last_frame = g->frame;
    return t->tex;
}

static void draw_images(tt__gl *g, const tt__layer *L, int w, int h)
{
    if (L->images.n == 0) return;
    g->UseProgram(g->prog_tex);
    g->Uniform2f(g->size_tex, (float)w, (float)h);
    g->Uniform1i(g->sampler, 0);
    g->ActiveTexture(GL_TEXTURE0);
    g->BindBuffer(GL_ARRAY_BUFFER, g->vbo);
    g->EnableVertexAttribArray(A_POS);
    g->EnableVertexAttribArray(A_COLOR);
    g->EnableVertexAttribArray(A_UV);
    for (size_t i = 0; i < L->images.n; i++) {
        const tt__imgdraw *d = &L->images.v[i];
        if (!texture_of(g, d->img)) continue;
        g->BufferData(GL_ARRAY_BUFFER, sizeof d->q, d->q, GL_STREAM_DRAW);
        size_t st = sizeof(tt__vtex);
        g->VertexAttribPointer(A_POS, 2, GL_FLOAT, GL_FALSE, (GLsizei)st, (void *)offsetof(tt__vtex, x));
        g->VertexAttribPointer(A_UV, 2, GL_FLOAT, GL_FALSE, (GLsizei)st, (void *)offsetof(tt__vtex, u));
        g->VertexAttribPointer(A_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE, (GLsizei)st, (void *)offsetof(tt__vtex, rgba));
        g->DrawArrays(GL_TRIANGLE_FAN, 0, 4);
        g->draw_calls++;
    }
    g->DisableVertexAttribArray(A_POS);
    g->DisableVertexAttribArray(A_COLOR);
    g->DisableVertexAttribArray(A_UV);
}

tt_result tt__gl_draw(tt__gl *g, const tt_canvas *c, int w, int h, char *err, size_t n)
{
    g->frame++;
    g->draw_calls = 0;
    g->Viewport(0, 0, w, h);
    g->ClearColor(c->background.r / 255.0f, c->background.g / 255.0f, c->background.b / 255.0f, c->background.a / 255.0f);
    g->Clear(GL_COLOR_BUFFER_BIT);
    g->Enable(GL_BLEND);
    g->Enable(GL_VERTEX_PROGRAM_POINT_SIZE); /* gl_PointSize from the shader */
    /* alpha of the target accumulates as "over", so an opaque background stays opaque */
    g->BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    for (int l = 0; l < 2; l++) {
        const tt__layer *L = &c->layers[l];
        draw_images(g, L, w, h);
        draw_solid(g, &L->tris, w, h);
        if (!draw_points(g, &L->points, w, h) || !draw_circles(g, &L->circles, w, h)) {
            tt__errf(err, n, "out of memory for the circle index buffer");
            return TT_ENOMEM;
        }
        draw_solid(g, &L->text, w, h);
    }
    g->UseProgram(0);
    /* textures of images not drawn for a while are dropped */
    for (size_t i = 0; i < g->ntex;) {
        if (g->frame - g->tex[i].last_frame > 120) {
            g->DeleteTextures(1, &g->tex[i].tex);
            g->tex[i] = g->tex[--g->ntex];
        } else {
            i++;
        }
    }
    GLenum e = g->GetError();
    if (e != GL_NO_ERROR) {
        tt__errf(err, n, "OpenGL error 0x%04x while drawing", (unsigned)e);
        return TT_ESTATE;
    }
    return TT_OK;
}

void tt__gl_read(tt__gl *g, int w, int h, uint8_t *out)
{
    g->Finish();
    g->PixelStorei(GL_PACK_ALIGNMENT, 1);
    g->ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out);
}

void tt__gl_finish(tt__gl *g) { g->Finish(); }

unsigned tt__gl_draw_calls(const tt__gl *g) { return g ? g->draw_calls : 0; }
