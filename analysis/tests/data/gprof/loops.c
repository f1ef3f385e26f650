/* A program with known call counts, for reading gprof's output of its -pg build
 * (analysis/tests/gprof_import.rs, and the fixtures beside this file):
 *   main -> f 1000 times, f -> g 3 times each (g: 3000 calls);
 *   main -> even(10) 100 times: even and odd call each other (one cycle), 11 calls a
 *   round from main's one: even 600 (100 from main, 500 from odd), odd 500;
 *   main -> fact(5) 100 times: fact calls itself 4 times a round (100+400).
 * g does most of the work; the cycle and fact some. Build: gcc -pg -O1 loops.c.
 */
#include <stdio.h>

volatile double sink;

__attribute__((noinline)) double g(int i)
{
    double s = 0;
    for (int k = 0; k < 60000; k++)
        s += (double)k * i;
    return s;
}

__attribute__((noinline)) double f(int i)
{
    double s = 0;
    for (int j = 0; j < 3; j++)
        s += g(i + j);
    return s;
}

__attribute__((noinline)) double even(int n);

__attribute__((noinline)) double odd(int n)
{
    for (int k = 0; k < 40000; k++)
        sink += k;
    return n == 0 ? 0 : even(n - 1);
}

__attribute__((noinline)) double even(int n)
{
    for (int k = 0; k < 40000; k++)
        sink += k;
    return n == 0 ? 1 : odd(n - 1);
}

__attribute__((noinline)) long fact(int n)
{
    for (int k = 0; k < 40000; k++)
        sink += k;
    return n <= 1 ? 1 : n * fact(n - 1);
}

int main(void)
{
    double t = 0;
    for (int i = 0; i < 1000; i++)
        t += f(i);
    for (int i = 0; i < 100; i++)
        t += even(10);
    for (int i = 0; i < 100; i++)
        t += fact(5);
    sink = t;
    printf("%g\n", t);
    return 0;
}
