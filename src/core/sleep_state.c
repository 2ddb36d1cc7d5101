/* tether — sleeping's per-slot arrays, grown and freed: apart from the
 * feature (sleep.c) so that its snapshot section (sleep_stream.c), which
 * makes a state to load into, and the feature, which names that section's
 * hooks, do not use each other. */
#include "sleep_internal.h"

#include <stdlib.h>

bool tt__sleep_grow(tt__sleep *s, uint32_t n)
{
    if (n <= s->cap) return true;
    uint32_t cap = s->cap ? s->cap : 64;
    while (cap < n) cap *= 2;
    double **d[] = {&s->rest, &s->held, &s->ax, &s->ay, &s->mx, &s->my, &s->minrest};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++) {
        double *q = realloc(*d[k], (size_t)cap * sizeof *q);
        if (!q) return false;
        *d[k] = q;
    }
    uint32_t *is = realloc(s->island, (size_t)cap * sizeof *is);
    if (!is) return false;
    s->island = is;
    uint64_t *sn = realloc(s->seen, (size_t)cap * sizeof *sn);
    if (!sn) return false;
    s->seen = sn;
    uint32_t *rg = realloc(s->ring, (size_t)cap * sizeof *rg);
    if (!rg) return false;
    s->ring = rg;
    uint32_t *p = realloc(s->parent, (size_t)cap * sizeof *p);
    if (!p) return false;
    s->parent = p;
    uint32_t *hl = realloc(s->holders.list, (size_t)cap * sizeof *hl);
    if (!hl) return false;
    s->holders.list = hl;
    if (s->wake_cap < cap) { /* an island per particle at most: waking at a step allocates nothing */
        uint64_t *k = realloc(s->wake, (size_t)cap * sizeof *k);
        if (!k) return false;
        s->wake = k;
        s->wake_cap = cap;
    }
    for (uint32_t i = s->cap; i < cap; i++) {
        s->rest[i] = s->held[i] = s->ax[i] = s->ay[i] = s->mx[i] = s->my[i] = 0.0;
        s->island[i] = s->ring[i] = 0;
        s->seen[i] = 0;
    }
    s->cap = cap;
    return true;
}

void tt__sleep_destroy(tt_world *w, void *self)
{
    (void)w;
    tt__sleep *s = self;
    if (!s) return;
    free(s->rest); free(s->held); free(s->seen); free(s->ax); free(s->ay); free(s->mx); free(s->my); free(s->island); free(s->ring); free(s->parent); free(s->minrest); free(s->wake); free(s->holders.list);
    free(s->grid.start); free(s->grid.idx);
    tt__sleep_scratch_free(w, s);
    free(s);
}

int tt__sleep_cmp_u64(const void *a, const void *b)
{
    const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

bool tt__sleep_link_rings(const tt_world *w, tt__sleep *s)
{
    const uint32_t n = tt__sleep_covered(w, s);
    uint64_t *key = malloc(((size_t)s->asleep + 1) * sizeof *key);
    if (!key) return false;
    uint32_t m = 0; /* (island, slot): each island's sleepers side by side */
    for (uint32_t i = 0; i < n && m < s->asleep; i++)
        if (s->island[i]) key[m++] = (uint64_t)s->island[i] << 32 | i;
    qsort(key, m, sizeof *key, tt__sleep_cmp_u64);
    for (uint32_t a = 0, b; a < m; a = b) {
        for (b = a + 1; b < m && key[b] >> 32 == key[a] >> 32; b++) s->ring[(uint32_t)key[b - 1]] = (uint32_t)key[b];
        s->ring[(uint32_t)key[b - 1]] = (uint32_t)key[a];
    }
    free(key);
    return true;
}
