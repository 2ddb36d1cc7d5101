/* tether — snapshot files: a payload behind a 48-byte header, all numbers
 * little-endian whatever the machine:
 *
 *   0  magic "\x89TTS\r\n\x1a\n" (8: the high bit and the line ends catch a
 *      file mangled by a text-mode copy, as PNG's does)
 *   8  file format version (u32)      12 header size (u32, 48)
 *   16 engine version that wrote it: major, minor, patch (u16 each)
 *   22 payload kind (u16, snapfile.h)  24 payload length (u64)
 *   32 zero (u64, reserved)            40 checksum (u64) of bytes 0..40 and the payload
 *
 * The engine version is there for the error message and for people: what
 * decides whether a file can be read is the format version here and the
 * stream's own version inside. A save writes path.tmp and renames it over
 * path, so the old file survives a crash or a full disk. */
#include "snapfile.h"
#include "stream.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { FILE_VERSION = 1, HEADER = 48 };
static const unsigned char file_magic[8] = {0x89, 'T', 'T', 'S', '\r', '\n', 0x1a, '\n'};

static void le_put(unsigned char *p, uint64_t v, int n)
{
    for (int i = 0; i < n; i++) p[i] = (unsigned char)(v >> (8 * i));
}

static uint64_t le_get(const unsigned char *p, int n)
{
    uint64_t v = 0;
    for (int i = n - 1; i >= 0; i--) v = v << 8 | p[i];
    return v;
}

static uint64_t checksum(const unsigned char *header, const void *payload, size_t n)
{
    tt__hasher h;
    tt__hasher_init(&h);
    tt__hasher_feed(&h, header, 40);
    if (n) tt__hasher_feed(&h, payload, n);
    return tt__hasher_end(&h);
}

bool tt__file_write(const char *path, unsigned kind, const void *payload, size_t n, char *why, size_t whylen)
{
    unsigned char h[HEADER] = {0};
    memcpy(h, file_magic, 8);
    le_put(h + 8, FILE_VERSION, 4);
    le_put(h + 12, HEADER, 4);
    le_put(h + 16, TT_VERSION_MAJOR, 2);
    le_put(h + 18, TT_VERSION_MINOR, 2);
    le_put(h + 20, TT_VERSION_PATCH, 2);
    le_put(h + 22, kind, 2);
    le_put(h + 24, n, 8);
    le_put(h + 40, checksum(h, payload, n), 8);
    size_t plen = strlen(path);
    char *tmp = malloc(plen + 5);
    if (!tmp) { snprintf(why, whylen, "out of memory"); return false; }
    memcpy(tmp, path, plen);
    memcpy(tmp + plen, ".tmp", 5);
    FILE *f = fopen(tmp, "wb");
    if (!f) {
        snprintf(why, whylen, "cannot open '%s' for writing: %s", tmp, strerror(errno));
        free(tmp);
        return false;
    }
    bool ok = fwrite(h, 1, HEADER, f) == HEADER && (n == 0 || fwrite(payload, 1, n, f) == n);
    int err = errno;
    ok = (fclose(f) == 0) && ok;
    if (ok && rename(tmp, path) != 0) {
        err = errno;
        ok = false;
    }
    if (!ok) {
        snprintf(why, whylen, "cannot write '%s': %s", path, strerror(err));
        remove(tmp);
    }
    free(tmp);
    return ok;
}

/* The header's fields checked; the payload length in *len. */
static bool check_header(const unsigned char *h, size_t got, long long rest, unsigned *kind, uint64_t *len, char *why,
                         size_t whylen)
{
    if (got < 8 || memcmp(h, file_magic, 8) != 0) {
        snprintf(why, whylen, "not a tether snapshot file (no tether file signature at its start)");
        return false;
    }
    if (got < HEADER) { snprintf(why, whylen, "truncated: %zu bytes, shorter than the %d-byte header", got, HEADER); return false; }
    const unsigned version = (unsigned)le_get(h + 8, 4);
    if (version != FILE_VERSION || le_get(h + 12, 4) != HEADER) {
        snprintf(why, whylen, "file format version %u (written by tether %u.%u.%u), this build (%s) reads version %d",
                 version, (unsigned)le_get(h + 16, 2), (unsigned)le_get(h + 18, 2), (unsigned)le_get(h + 20, 2),
                 TT_VERSION_STRING, FILE_VERSION);
        return false;
    }
    *kind = (unsigned)le_get(h + 22, 2);
    *len = le_get(h + 24, 8);
    if (*kind >= TT__FILE_KINDS) { snprintf(why, whylen, "unknown payload kind %u (corrupted?)", *kind); return false; }
    if (rest < 0 || (uint64_t)rest != *len) {
        snprintf(why, whylen, "%lld payload bytes, the header says %llu (truncated or padded)", rest, (unsigned long long)*len);
        return false;
    }
    return true;
}

unsigned char *tt__file_read(const char *path, unsigned *kind, size_t *n, char *why, size_t whylen)
{
    FILE *f = fopen(path, "rb");
    if (!f) { snprintf(why, whylen, "cannot open '%s': %s", path, strerror(errno)); return NULL; }
    unsigned char h[HEADER];
    size_t got = fread(h, 1, HEADER, f);
    long long rest = -1;
    if (got == HEADER && fseek(f, 0, SEEK_END) == 0) {
        long end = ftell(f);
        rest = end < 0 ? -1 : (long long)end - HEADER;
        if (fseek(f, HEADER, SEEK_SET) != 0) rest = -1;
    }
    uint64_t len = 0;
    unsigned char *p = NULL;
    if (!check_header(h, got, rest, kind, &len, why, whylen)) goto out;
    if (len > SIZE_MAX - 1 || !(p = malloc(len ? (size_t)len : 1))) { snprintf(why, whylen, "out of memory for %llu bytes", (unsigned long long)len); goto out; }
    if (fread(p, 1, (size_t)len, f) != (size_t)len) {
        snprintf(why, whylen, "cannot read '%s' (truncated while reading?)", path);
    } else if (le_get(h + 40, 8) != checksum(h, p, (size_t)len)) {
        snprintf(why, whylen, "checksum mismatch (corrupted)");
    } else {
        *n = (size_t)len;
        fclose(f);
        return p;
    }
    free(p);
    p = NULL;
out:
    fclose(f);
    return p;
}

const unsigned char *tt__file_stream(const unsigned char *payload, unsigned kind, size_t n, size_t *size, char *why,
                                     size_t whylen)
{
    if (kind == TT__FILE_STREAM) {
        *size = n;
        return payload;
    }
    if (kind == TT__FILE_JOURNAL) {
        snprintf(why, whylen, "it holds a replay journal, not a snapshot (tt_journal_load_file)");
        return NULL;
    }
    if (kind != TT__FILE_LUA || n < 16 || memcmp(payload, "TTLU", 4) != 0 || le_get(payload + 8, 8) > n - 16) {
        snprintf(why, whylen, "the file holds no snapshot");
        return NULL;
    }
    *size = (size_t)le_get(payload + 8, 8);
    return payload + 16;
}

/* ---- the public calls ------------------------------------------------------------ */

tt_result tt_world_save_file(const tt_world *w, const char *path)
{
    TT_CHECK_WORLD(w, "tt_world_save_file");
    if (!path || !*path) return tt__fail(w, TT_EINVAL, "tt_world_save_file: path is %s", path ? "empty" : "NULL");
    size_t n = 0;
    tt_world_save(w, NULL, 0, &n);
    unsigned char *b = malloc(n ? n : 1);
    if (!b) return tt__fail(w, TT_ENOMEM, "tt_world_save_file: out of memory for %zu bytes", n);
    tt_result r = tt_world_save(w, b, n, &n);
    char why[300];
    if (r == TT_OK && !tt__file_write(path, TT__FILE_STREAM, b, n, why, sizeof why)) {
        r = TT_EINVAL;
        tt__fail(w, r, "tt_world_save_file: %s", why);
    }
    free(b);
    return r;
}

/* The stream in the file at path (free *buf), or NULL with why. */
static const unsigned char *read_stream(const char *path, unsigned char **buf, size_t *size, char *why, size_t whylen)
{
    unsigned kind = 0;
    size_t n = 0;
    *buf = tt__file_read(path, &kind, &n, why, whylen);
    return *buf ? tt__file_stream(*buf, kind, n, size, why, whylen) : NULL;
}

tt_result tt_world_restore_file(tt_world *w, const char *path)
{
    TT_CHECK_WORLD(w, "tt_world_restore_file");
    if (!path || !*path) return tt__fail(w, TT_EINVAL, "tt_world_restore_file: path is %s", path ? "empty" : "NULL");
    char why[300];
    unsigned char *buf;
    size_t size = 0;
    const unsigned char *s = read_stream(path, &buf, &size, why, sizeof why);
    tt_result r = s ? tt_world_restore(w, s, size) : TT_EINVAL;
    if (r != TT_OK && s) snprintf(why, sizeof why, "%s", tt_last_error(w));
    free(buf);
    if (r != TT_OK) return tt__fail(w, r, "tt_world_restore_file: '%s': %s%s", path, why, s ? "" : "; the world is unchanged");
    return TT_OK;
}

tt_world *tt_world_load_file(const char *path)
{
    if (!path || !*path) {
        tt__fail(NULL, TT_EINVAL, "tt_world_load_file: path is %s", path ? "empty" : "NULL");
        return NULL;
    }
    char why[300];
    unsigned char *buf;
    size_t size = 0;
    const unsigned char *s = read_stream(path, &buf, &size, why, sizeof why);
    tt_world *w = s ? tt_world_load(s, size) : NULL;
    if (!w && s) snprintf(why, sizeof why, "%s", tt_last_error(NULL));
    free(buf);
    if (!w) tt__fail(NULL, TT_EINVAL, "tt_world_load_file: '%s': %s", path, why);
    return w;
}
