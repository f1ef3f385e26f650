/* every_macro.c compiled as C++ (the scoped RTPROF_PHASE only exists there). */
#include "rtprof.h"

#ifdef __cplusplus
extern "C" {
#endif
void count_in_other_unit(int n);
#ifdef __cplusplus
}
#endif

int main(void) {
    int i;
    RTPROF_DECLARE_COUNTER(RTPROF_USER_COUNTER(3), "main's own");
    RTPROF_DECLARE_PHASE(RTPROF_USER_PHASE(1), "outer");
    RTPROF_PHASE_BEGIN(RTPROF_USER_PHASE(1));
    for (i = 0; i < 10; i++) {
        RTPROF_PHASE_BEGIN(RTPROF_PHASE_CLOSEST_HIT);
        RTPROF_COUNT(RTPROF_CALLS_TRACE, 1);
        RTPROF_COUNT(RTPROF_USER_COUNTER(3), 2);
        RTPROF_PHASE_END(RTPROF_PHASE_CLOSEST_HIT);
    }
#ifdef __cplusplus
    {
        RTPROF_PHASE(RTPROF_PHASE_SHADING);
        RTPROF_COUNT(RTPROF_CALLS_SHADE, 5);
    }
#endif
    RTPROF_PHASE_END(RTPROF_USER_PHASE(1));
    /* An end without its begin is counted, not obeyed. */
    RTPROF_PHASE_END(RTPROF_PHASE_TRAVERSAL);
    count_in_other_unit(7);
    return RTPROF_ENABLED() ? 0 : 3;
}
