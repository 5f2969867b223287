/* Independent reference for Kapitza's pendulum (issue 11):
 *   theta'' = (a + (b/eps) cos(t/eps)) sin(theta)
 * integrated by a fixed-step Taylor-series method of order N in 80-bit long double.
 * Taylor coefficients come from the usual recurrences (sin/cos of a series, Cauchy
 * products); the forcing's coefficients are exact. Step h = min(eps, 0.1) / 2, so each step
 * spans a quarter of a fast radian-period and the terms fall like (h/eps)^n / n!.
 * It shares no code with the Rust crate.
 *
 * usage: kapitza_taylor a b eps theta0 theta_dot0 t_end nsamples [refine]
 * prints one line "t theta theta_dot" at t = i t_end / nsamples, i = 0..nsamples, with 21
 * significant digits; refine (default 1) divides the step, for the accuracy check. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define N 28

static long double A, B, EPS;

static void taylor_step(long double t0, long double *th, long double *p, long double h) {
    long double T[N + 2], P[N + 2], S[N + 1], C[N + 1], F[N + 1], G[N + 1];
    long double ph = t0 / EPS;
    long double c0 = cosl(ph), s0 = sinl(ph);
    long double pre = B / EPS, fact = 1.0L;
    for (int j = 0; j <= N; j++) {
        long double trig;
        switch (j % 4) {
        case 0: trig = c0; break;
        case 1: trig = -s0; break;
        case 2: trig = -c0; break;
        default: trig = s0; break;
        }
        if (j > 0) fact *= (long double)j * EPS; /* j! eps^j */
        F[j] = pre * trig / fact;
    }
    F[0] += A;
    T[0] = *th;
    P[0] = *p;
    S[0] = sinl(*th);
    C[0] = cosl(*th);
    for (int k = 0; k <= N; k++) {
        if (k >= 1) {
            long double s = 0, c = 0;
            for (int j = 1; j <= k; j++) {
                s += j * T[j] * C[k - j];
                c -= j * T[j] * S[k - j];
            }
            S[k] = s / k;
            C[k] = c / k;
        }
        long double g = 0;
        for (int j = 0; j <= k; j++) g += F[j] * S[k - j];
        G[k] = g;
        T[k + 1] = P[k] / (k + 1);
        P[k + 1] = G[k] / (k + 1);
    }
    long double nt = 0, np = 0;
    for (int k = N; k >= 0; k--) {
        nt = nt * h + T[k];
        np = np * h + P[k];
    }
    *th = nt;
    *p = np;
}

int main(int argc, char **argv) {
    if (argc != 8 && argc != 9) {
        fprintf(stderr, "usage: %s a b eps theta0 theta_dot0 t_end nsamples [refine]\n", argv[0]);
        return 2;
    }
    A = strtold(argv[1], 0);
    B = strtold(argv[2], 0);
    EPS = strtold(argv[3], 0);
    long double th = strtold(argv[4], 0), p = strtold(argv[5], 0);
    long double t_end = strtold(argv[6], 0);
    long n = atol(argv[7]);
    long double hmax = (EPS < 0.1L ? EPS : 0.1L) / 2 / (argc == 9 ? atol(argv[8]) : 1);
    printf("%.21Lg %.21Lg %.21Lg\n", 0.0L, th, p);
    long double t = 0;
    for (long i = 1; i <= n; i++) {
        long double target = t_end * i / n;
        long steps = (long)ceill((target - t) / hmax);
        long double h = (target - t) / steps;
        long double t_start = t;
        for (long s = 0; s < steps; s++) {
            taylor_step(t_start + s * h, &th, &p, h);
        }
        t = target;
        printf("%.21Lg %.21Lg %.21Lg\n", t, th, p);
    }
    return 0;
}
