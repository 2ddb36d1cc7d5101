/* tether — the keyframe delta codec. A keyframe is a snapshot stream, and
 * consecutive keyframes of one world share their layout: the same fields
 * at the same offsets while the handle pools keep their size. So:
 *
 *   1. XOR with the reference: what did not change (settings, masses,
 *      radii, handles, resting particles) becomes zero bytes;
 *   2. byte planes: the buffer as 8-byte words, byte k of every word
 *      together (tail bytes as they are). A double that moved a little
 *      keeps its sign, exponent and high mantissa, so after the XOR its
 *      high bytes are zero; in planes those zeros make long runs instead
 *      of two zeros between six changed bytes in every word;
 *   3. runs: (zeros, literals) pairs of LEB128 counts, literals following.
 *
 * Coding: "TTD1", length (u64 LEB128), then the runs. A coding decodes
 * only against the reference it was made with (the ring keeps them so). */
#include "delta.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

size_t tt__leb_put(unsigned char *p, uint64_t v)
{
    size_t n = 0;
    do {
        unsigned char b = v & 0x7f;
        v >>= 7;
        p[n++] = b | (v ? 0x80 : 0);
    } while (v);
    return n;
}

bool tt__leb_get(const unsigned char *d, size_t dn, size_t *at, uint64_t *v)
{
    *v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
        if (*at >= dn) return false;
        unsigned char b = d[(*at)++];
        *v |= (uint64_t)(b & 0x7f) << shift;
        if (!(b & 0x80)) return true;
    }
    return false;
}

bool tt__delta_encode(const unsigned char *t, size_t tn, const unsigned char *r, size_t rn, unsigned char **out,
                      size_t *outn)
{
    unsigned char *x = malloc(tn ? tn : 1);
    /* worst case: every byte a literal, a run header per 2^63 bytes: header and a few counts */
    unsigned char *o = malloc(tn + tn / 64 + 32);
    if (!x || !o) {
        free(x);
        free(o);
        return false;
    }
    const size_t words = tn / 8, body = words * 8;
    for (size_t s = 0; s < tn; s++) o[s] = t[s] ^ (s < rn ? r[s] : 0); /* o as scratch: it is tn bytes or more */
    for (size_t p = 0; p < 8 && words; p++)
        for (size_t k = 0; k < words; k++) x[p * words + k] = o[k * 8 + p];
    memcpy(x + body, o + body, tn - body);
    size_t n = 0;
    memcpy(o, "TTD1", 4);
    n = 4 + tt__leb_put(o + 4, tn);
    for (size_t i = 0; i < tn;) {
        size_t z = i;
        while (z < tn && x[z] == 0) z++;
        /* a literal run ends at the first 3 zeros in a row (shorter zero runs cost more as runs) */
        size_t l = z;
        while (l < tn && !(x[l] == 0 && l + 2 < tn && x[l + 1] == 0 && x[l + 2] == 0)) l++;
        n += tt__leb_put(o + n, z - i);
        n += tt__leb_put(o + n, l - z);
        memcpy(o + n, x + z, l - z);
        n += l - z;
        i = l;
    }
    free(x);
    unsigned char *shrunk = realloc(o, n);
    *out = shrunk ? shrunk : o;
    *outn = n;
    return true;
}

size_t tt__delta_length(const unsigned char *d, size_t dn)
{
    size_t at = 4;
    uint64_t tn;
    if (dn < 5 || memcmp(d, "TTD1", 4) != 0 || !tt__leb_get(d, dn, &at, &tn) || tn > SIZE_MAX) return 0;
    return (size_t)tn;
}

bool tt__delta_decode(const unsigned char *d, size_t dn, const unsigned char *r, size_t rn, unsigned char *t, size_t tn)
{
    size_t at = 4;
    uint64_t len;
    if (dn < 5 || memcmp(d, "TTD1", 4) != 0 || !tt__leb_get(d, dn, &at, &len) || len != tn) return false;
    unsigned char *x = malloc(tn ? tn : 1);
    if (!x) return false;
    size_t i = 0;
    bool ok = true;
    while (ok && i < tn) {
        uint64_t z, l;
        ok = tt__leb_get(d, dn, &at, &z) && tt__leb_get(d, dn, &at, &l) && z <= tn - i && l <= tn - i - z && l <= dn - at &&
             (z | l) != 0;
        if (!ok) break;
        memset(x + i, 0, (size_t)z);
        memcpy(x + i + z, d + at, (size_t)l);
        at += (size_t)l;
        i += (size_t)(z + l);
    }
    if (ok && at == dn) {
        const size_t words = tn / 8, body = words * 8;
        for (size_t p = 0; p < 8 && words; p++)
            for (size_t k = 0; k < words; k++) t[k * 8 + p] = x[p * words + k];
        memcpy(t + body, x + body, tn - body);
        const size_t m = rn < tn ? rn : tn;
        for (size_t k = 0; k < m; k++) t[k] ^= r[k];
    }
    free(x);
    return ok && at == dn;
}

size_t tt__delta_check(const unsigned char *d, size_t dn, size_t max)
{
    const size_t tn = tt__delta_length(d, dn);
    if (tn == 0 || tn > max) return 0;
    size_t at = 4, i = 0;
    uint64_t len;
    tt__leb_get(d, dn, &at, &len);
    while (i < tn) {
        uint64_t z, l;
        if (!tt__leb_get(d, dn, &at, &z) || !tt__leb_get(d, dn, &at, &l) || z > tn - i || l > tn - i - z ||
            l > dn - at || (z | l) == 0)
            return 0;
        at += (size_t)l;
        i += (size_t)(z + l);
    }
    return at == dn ? tn : 0;
}
