/* tether — files that hold a payload (a snapshot stream, the Lua binding's
 * snapshot with user values, a replay journal) behind a versioned header
 * and a checksum, written so that a crash mid-save never leaves a torn file
 * in the place of a good one. The snapshot stream has its own header; this
 * one wraps it (and other payloads) without knowing what is inside. */
#ifndef TETHER_SNAPFILE_H
#define TETHER_SNAPFILE_H

#include <stdbool.h>
#include <stddef.h>

/* What a file's payload is. */
enum {
    TT__FILE_STREAM = 0,  /* tt_world_save's stream */
    TT__FILE_LUA = 1,     /* the Lua binding's envelope: "TTLU", u32 version, u64 stream length, stream, user values */
    TT__FILE_JOURNAL = 2, /* a replay journal's bytes (journal_file.c) */
    TT__FILE_KINDS = 3
};

/* Writes payload[0..n) of the kind to path (through path.tmp and a rename).
 * False with the reason in why. */
bool tt__file_write(const char *path, unsigned kind, const void *payload, size_t n, char *why, size_t whylen);
/* Reads and checks a file: its payload in new memory (free it) and its kind;
 * NULL with the reason in why (cannot open, not a tether file, another
 * format version, truncated or longer than its header says, checksum). */
unsigned char *tt__file_read(const char *path, unsigned *kind, size_t *n, char *why, size_t whylen);
/* The snapshot stream inside a payload of kind TT__FILE_STREAM or
 * TT__FILE_LUA; NULL with why when the payload holds none. */
const unsigned char *tt__file_stream(const unsigned char *payload, unsigned kind, size_t n, size_t *size,
                                     char *why, size_t whylen);

#endif
