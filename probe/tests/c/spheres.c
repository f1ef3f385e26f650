/* A brute-force sphere tracer instrumented with rtprof.h: the probe's test fixture.
 *
 *   spheres W H THREADS FRAMES      render FRAMES frames of W x H, print a checksum
 *   spheres W H THREADS loop        render until killed; "ready" after the first frame
 *   spheres scene                   print the scene ("sphere x y z r", one a line)
 *
 * A pinhole camera at the origin looks down -z through pixel centres (90 degrees
 * horizontally); every eye ray tests every sphere (no acceleration), so the sphere
 * tests are W * H * SPHERES per frame. The hits are what the tests compute
 * independently. Rows go to THREADS pthreads in turn. Counting is done the cheap way a
 * brute-force loop allows: the tests and hits of one ray are added once, after its
 * loop; the sphere loop is one phase.
 */
#include "rtprof.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SPHERES 32

struct sphere {
    double x, y, z, r;
};

static struct sphere scene[SPHERES];
static int width, height, threads, frames, forever;
static double checksum[64];

/* 32 spheres on a 8 x 4 grid at depths 4.5..9.8, overlapping on screen, some partly
 * out of view; no eye ray grazes one (the tests check the margin). */
static void build_scene(void) {
    int k;
    for (k = 0; k < SPHERES; k++) {
        scene[k].x = -3.5 + 1.0 * (k % 8) + 0.15 * (k % 3);
        scene[k].y = -1.6 + 1.05 * (k / 8) - 0.1 * (k % 5);
        scene[k].z = -4.5 - 0.17 * (double)((k * 7) % SPHERES);
        scene[k].r = 0.45 + 0.06 * (k % 7);
    }
}

/* The nearest hit of the ray (origin at 0) with direction d, or -1. */
static int trace(const double d[3], double *t_hit, int *hits) {
    int k, nearest = -1, n = 0;
    double best = 1e30;
    RTPROF_PHASE_BEGIN(RTPROF_PHASE_SPHERE_TEST);
    for (k = 0; k < SPHERES; k++) {
        const struct sphere *s = &scene[k];
        /* |t d - c|^2 = r^2 with |d| = 1: t^2 - 2 b t + c = 0 */
        double b = d[0] * s->x + d[1] * s->y + d[2] * s->z;
        double c = s->x * s->x + s->y * s->y + s->z * s->z - s->r * s->r;
        double disc = b * b - c;
        if (disc >= 0) {
            double root = sqrt(disc);
            double t = b - root > 1e-9 ? b - root : b + root;
            if (t > 1e-9) {
                n++;
                if (t < best) {
                    best = t;
                    nearest = k;
                }
            }
        }
    }
    RTPROF_PHASE_END(RTPROF_PHASE_SPHERE_TEST);
    RTPROF_COUNT(RTPROF_TESTS_SPHERE_TESTS, SPHERES);
    RTPROF_COUNT(RTPROF_TESTS_SPHERE_HITS, n);
    *t_hit = best;
    *hits = n;
    return nearest;
}

static double shade(const double d[3], double t, int k) {
    static const double light[3] = {0.577350269, 0.577350269, 0.577350269};
    double p[3], nrm[3], lambert;
    int i;
    RTPROF_PHASE_BEGIN(RTPROF_PHASE_SHADING);
    p[0] = t * d[0];
    p[1] = t * d[1];
    p[2] = t * d[2];
    nrm[0] = (p[0] - scene[k].x) / scene[k].r;
    nrm[1] = (p[1] - scene[k].y) / scene[k].r;
    nrm[2] = (p[2] - scene[k].z) / scene[k].r;
    lambert = 0;
    for (i = 0; i < 3; i++) lambert += nrm[i] * light[i];
    RTPROF_PHASE_END(RTPROF_PHASE_SHADING);
    return lambert > 0 ? lambert : 0;
}

static double render_row(int j) {
    double sum = 0, aspect = (double)height / width;
    int i;
    for (i = 0; i < width; i++) {
        double d[3], len, t;
        int k, hits;
        RTPROF_PHASE_BEGIN(RTPROF_PHASE_CAMERA_RAY);
        d[0] = 2.0 * (i + 0.5) / width - 1.0;
        d[1] = (1.0 - 2.0 * (j + 0.5) / height) * aspect;
        d[2] = -1.0;
        len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        d[0] /= len;
        d[1] /= len;
        d[2] /= len;
        RTPROF_COUNT(RTPROF_RAYS_PRIMARY, 1);
        RTPROF_PHASE_END(RTPROF_PHASE_CAMERA_RAY);
        RTPROF_PHASE_BEGIN(RTPROF_PHASE_CLOSEST_HIT);
        k = trace(d, &t, &hits);
        RTPROF_PHASE_END(RTPROF_PHASE_CLOSEST_HIT);
        if (k >= 0) {
            RTPROF_COUNT(RTPROF_RAYS_PRIMARY_HIT, 1);
            sum += shade(d, t, k) + hits;
        }
    }
    return sum;
}

static void *worker(void *arg) {
    int index = (int)(size_t)arg, frame, j;
    for (frame = 0; forever || frame < frames; frame++) {
        for (j = index; j < height; j += threads) checksum[index] += render_row(j);
        if (forever && frame == 0 && index == 0) {
            printf("ready\n");
            fflush(stdout);
        }
    }
    return NULL;
}

int main(int argc, char **argv) {
    pthread_t pool[64];
    double total = 0;
    int n;
    build_scene();
    if (argc == 2 && strcmp(argv[1], "scene") == 0) {
        for (n = 0; n < SPHERES; n++)
            printf("sphere %.17g %.17g %.17g %.17g\n", scene[n].x, scene[n].y, scene[n].z,
                   scene[n].r);
        return 0;
    }
    if (argc != 5) {
        fprintf(stderr, "usage: spheres W H THREADS FRAMES|loop, or spheres scene\n");
        return 2;
    }
    width = atoi(argv[1]);
    height = atoi(argv[2]);
    threads = atoi(argv[3]);
    forever = strcmp(argv[4], "loop") == 0;
    frames = forever ? 1 : atoi(argv[4]);
    if (width < 1 || height < 1 || threads < 1 || threads > 64 || frames < 1) {
        fprintf(stderr, "spheres: W, H and FRAMES at least 1, THREADS 1 to 64\n");
        return 2;
    }
    RTPROF_DECLARE_COUNTER(RTPROF_USER_COUNTER(0), "fixture frames");
    RTPROF_DECLARE_PHASE(RTPROF_USER_PHASE(0), "fixture setup");
    RTPROF_PHASE_BEGIN(RTPROF_USER_PHASE(0));
    RTPROF_COUNT(RTPROF_USER_COUNTER(0), frames);
    RTPROF_PHASE_END(RTPROF_USER_PHASE(0));
    for (n = 0; n < threads; n++)
        if (pthread_create(&pool[n], NULL, worker, (void *)(size_t)n) != 0) return 1;
    for (n = 0; n < threads; n++) pthread_join(pool[n], NULL);
    for (n = 0; n < threads; n++) total += checksum[n];
    printf("%.6f\n", total);
    return 0;
}
