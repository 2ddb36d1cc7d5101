/* tether — a byte delta codec for keyframes (the rewind ring): a buffer
 * coded against a reference buffer of about the same layout. Our own code,
 * no dependency; see delta.c for the format and what it costs. */
#ifndef TETHER_DELTA_H
#define TETHER_DELTA_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Codes t[0..tn) against r[0..rn) (r may be NULL when rn is 0) into new
 * memory (*out, *outn); false when out of memory. */
bool tt__delta_encode(const unsigned char *t, size_t tn, const unsigned char *r, size_t rn, unsigned char **out,
                      size_t *outn);
/* The length of the buffer that d[0..dn) decodes to; 0 when d is not a coding. */
size_t tt__delta_length(const unsigned char *d, size_t dn);
/* Decodes d[0..dn) against r[0..rn) into t[0..tn) (tn from tt__delta_length);
 * false when d is not a valid coding. t and r may not overlap. */
bool tt__delta_decode(const unsigned char *d, size_t dn, const unsigned char *r, size_t rn, unsigned char *t, size_t tn);

/* Whether d[0..dn) is a well-formed coding of at most max bytes, without
 * decoding it: the length it decodes to, or 0. */
size_t tt__delta_check(const unsigned char *d, size_t dn, size_t max);
/* Unsigned LEB128 (the codec's counts; the replay journal's lengths):
 * put writes at most 10 bytes and returns how many; get reads at *at,
 * false when d ends first or the number runs past 64 bits. */
size_t tt__leb_put(unsigned char *p, uint64_t v);
bool tt__leb_get(const unsigned char *d, size_t dn, size_t *at, uint64_t *v);

#endif
