/* The second translation unit of every_macro.c: counts through the same state. */
#include "rtprof.h"

void count_in_other_unit(int n);

void count_in_other_unit(int n) {
    RTPROF_COUNT(RTPROF_CALLS_TRACE, n);
    RTPROF_COUNT(RTPROF_USER_COUNTER(5), 1);
}
