/* How many bytes a second this machine reads from memory, with 1 and 2 threads: the sum of a
 * 2 GB array of floats (4x the 480 MiB L3 cache of the CI machine), best of 5 passes. The
 * bound of a solve that streams its factors (BENCHMARKS.md, "What bounds a large model's
 * iteration").
 *
 *   gcc -O3 -march=native -ffast-math -fopenmp scripts/read_bandwidth.c -o /tmp/read_bandwidth
 *   /tmp/read_bandwidth
 */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

int main(void) {
    size_t n = 2000000000 / sizeof(float);
    float *a = malloc(n * sizeof(float));
    if (!a) return 1;
#pragma omp parallel for
    for (size_t i = 0; i < n; i++) a[i] = (float)i * 1e-9f;
    double keep = 0.0;
    for (int t = 1; t <= 2; t++) {
        omp_set_num_threads(t);
        double best = 1e30;
        for (int r = 0; r < 5; r++) {
            double t0 = omp_get_wtime();
            float acc = 0.0f;
#pragma omp parallel for reduction(+ : acc)
            for (size_t i = 0; i < n; i++) acc += a[i];
            double dt = omp_get_wtime() - t0;
            keep += acc;
            if (dt < best) best = dt;
        }
        printf("threads %d: %.1f GB/s\n", t, (double)(n * sizeof(float)) / best / 1e9);
    }
    printf("(checksum %g)\n", keep);
    free(a);
    return 0;
}
