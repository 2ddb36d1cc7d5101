/* tt__max, tt__min and tt__pick (src/core/internal.h) stand in for the
 * conditionals a > b ? a : b, a < b ? a : b and c ? a : b in the velocity
 * pass, the anchors and stacking's weights, where the goldens pin results
 * bit for bit: each gives the conditional's bits for every pair of special
 * values (signed zeros, infinities, NaNs of either sign, the smallest
 * subnormal). (Without SSE2 they are the conditionals themselves.) */
#include "test.h"
#include "core/internal.h"

#include <float.h>
#include <math.h>
#include <string.h>

static uint64_t bits(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static const double *values(int *n)
{
    static double v[14];
    const double list[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, INFINITY, -INFINITY, DBL_MIN, -DBL_MAX, 4.9e-324, 1e300};
    int k = 0;
    for (size_t i = 0; i < sizeof list / sizeof *list; i++) v[k++] = list[i];
    v[k++] = NAN;
    v[k++] = -NAN;
    *n = k;
    return v;
}

TEST(select_helpers_give_the_conditionals_bits_nan_and_signed_zeros_included)
{
    int n;
    const double *v = values(&n);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            const double a = v[i], b = v[j];
            ENSURE(bits(tt__max(a, b)) == bits(a > b ? a : b));
            ENSURE(bits(tt__min(a, b)) == bits(a < b ? a : b));
            ENSURE(bits(tt__pick(true, a, b)) == bits(a));
            ENSURE(bits(tt__pick(false, a, b)) == bits(b));
        }
}
