/* tether — C test runner. Ends with the line "N passed, M failed". */
#include "test.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#define MAX_TESTS 1024

static struct {
    const char *name, *file;
    tt_test_fn fn;
} tests[MAX_TESTS];
static int test_count;
static int current_failed;

void tt_test_register(const char *name, const char *file, tt_test_fn fn)
{
    if (test_count == MAX_TESTS) {
        fprintf(stderr, "too many tests\n");
        exit(2);
    }
    tests[test_count].name = name;
    tests[test_count].file = file;
    tests[test_count].fn = fn;
    test_count++;
}

void tt_test_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    fprintf(stdout, "    %s:%d: ", file, line);
    va_start(ap, fmt);
    vfprintf(stdout, fmt, ap);
    va_end(ap);
    fprintf(stdout, "\n");
    current_failed = 1;
}

static int by_file_then_name(const void *a, const void *b)
{
    const char *const *x = a, *const *y = b;
    int c = strcmp(x[1], y[1]);
    return c ? c : strcmp(x[0], y[0]);
}

int main(int argc, char **argv)
{
    const char *filter = argc > 1 ? argv[1] : NULL;
    /* Constructors run in link order; sort so the report reads the same everywhere. */
    qsort(tests, (size_t)test_count, sizeof tests[0], by_file_then_name);
    int passed = 0, failed = 0;
    for (int i = 0; i < test_count; i++) {
        if (filter && !strstr(tests[i].name, filter)) continue;
        current_failed = 0;
        tests[i].fn();
        printf("%s %s\n", current_failed ? "FAIL" : "ok  ", tests[i].name);
        fflush(stdout);
        if (current_failed) failed++; else passed++;
    }
    printf("%d passed, %d failed\n", passed, failed);
    fflush(stdout); /* a sanitizer exit must not swallow the summary line */
    return failed ? 1 : 0;
}
