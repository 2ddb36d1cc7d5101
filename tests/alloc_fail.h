/* tether tests — allocations that fail on demand, to check what a call
 * leaves behind when memory runs out half way through it. */
#ifndef TETHER_TEST_ALLOC_FAIL_H
#define TETHER_TEST_ALLOC_FAIL_H

#include <stdbool.h>

/* From the n-th allocation on (0: the very next), malloc, calloc and realloc
 * return NULL until tt_test_alloc_ok. */
void tt_test_alloc_fail_from(long n);
/* Allocations succeed again; true when one was refused since the last
 * tt_test_alloc_fail_from. */
bool tt_test_alloc_ok(void);
/* Allocation calls (malloc, calloc, realloc) made so far, refused or not. */
long tt_test_alloc_calls(void);
/* Where the first refused allocation since tt_test_alloc_fail_from was asked
 * for (a code address: addr2line -f -e build/test_c names the function). */
void *tt_test_alloc_refused_at(void);

#endif
