/* tether tests — allocation failure on demand. The test binary is linked
 * with --wrap for malloc, calloc and realloc (Makefile), so the engine's
 * calls come here; __real_* are the C library's (or the sanitizer's). */
#include "alloc_fail.h"

#include <stddef.h>

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t n);

static long countdown = -1; /* allocations left before they fail; -1: never */
static bool refused;
static long calls;
static void *refused_at; /* the code that asked for the first refused allocation */

/* Whether this allocation is to fail. */
static bool fail_now(void *site)
{
    calls++;
    if (countdown < 0) return false;
    if (countdown > 0) {
        countdown--;
        return false;
    }
    if (!refused) refused_at = site;
    refused = true;
    return true;
}

void *__wrap_malloc(size_t n) { return fail_now(__builtin_return_address(0)) ? NULL : __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t size) { return fail_now(__builtin_return_address(0)) ? NULL : __real_calloc(n, size); }
void *__wrap_realloc(void *p, size_t n) { return fail_now(__builtin_return_address(0)) ? NULL : __real_realloc(p, n); }

void tt_test_alloc_fail_from(long n)
{
    countdown = n;
    refused = false;
    refused_at = NULL;
}

long tt_test_alloc_calls(void) { return calls; }

void *tt_test_alloc_refused_at(void) { return refused_at; }

bool tt_test_alloc_ok(void)
{
    countdown = -1;
    return refused;
}
