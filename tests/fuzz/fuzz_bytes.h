/* tether — what the byte-stream fuzzers of test_c share (fuzz_stream.c,
 * fuzz_journal.c): a seeded generator, the mutations of a valid input, and
 * the loop that runs them for a CPU-time budget or a number of inputs. */
#ifndef TT_FUZZ_BYTES_H
#define TT_FUZZ_BYTES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct fuzz_buf {
    unsigned char *p;
    size_t n;
} fuzz_buf;

uint64_t fuzz_next(void);
size_t fuzz_below(size_t n);

/* A copy of base mutated one to three times: a bit flipped, a field set
 * by put_field, bytes deleted, repeated, spliced from other, or the input
 * cut short; the first keep bytes (a header the caller reseals) are never
 * touched. The caller frees .p. */
fuzz_buf fuzz_mutate(const fuzz_buf *base, const fuzz_buf *other, size_t keep, void (*put_field)(fuzz_buf *));

/* Seeds the generator from FUZZ_SEED (1 when unset), then runs
 * one(ctx, it, &accepted) for it = 0, 1, … until it fails, the inputs run
 * out or the CPU-time budget is spent. For what = "stream": the budget is
 * FUZZ_STREAM_SECONDS (make fuzz), the count FUZZ_STREAM_ITERATIONS (to
 * replay a failure) or else default_its (make test); it prints
 * "fuzz_stream: N streams, K accepted, seed S" (tests/fuzz/run.sh reads
 * it), or the line that replays a failure of the test named test. */
void fuzz_run(const char *what, const char *test, unsigned long default_its,
              bool (*one)(void *ctx, unsigned long it, uint32_t *accepted), void *ctx);

#endif
