/* Prints the glibc results that src/printf.rs's tests expect.
   Build and run: cc printf_fixture.c -o /tmp/pf -lm && /tmp/pf */
#include <math.h>
#include <stdio.h>

static void g(const char *fmt, double v) { printf("(\"%s\", %.17g) => \"", fmt, v); printf(fmt, v); printf("\"\n"); }
static void i(const char *fmt, long long v) { printf("(\"%s\", %lld) => \"", fmt, v); printf(fmt, v); printf("\"\n"); }

int main(void) {
  g("%g", 0.0); g("%g", -0.0); g("%g", 1.0); g("%g", 0.1);
  g("%g", 1.308996938995747); g("%g", 2.352424579); g("%g", 100000.0);
  g("%g", 1000000.0); g("%g", 999999.5); g("%g", 0.0001); g("%g", 0.00001);
  g("%g", 0.000123456789); g("%g", -12.841259972); g("%g", 1.5e300);
  g("%g", 5e-324); g("%g", 123456789.0);
  g("%.11g", -12.84125997234); g("%.11g", 1.308996938995747); g("%.11g", 0.01308996939);
  g("%.0g", 0.5); g("%.0g", 2.5); g("%#g", 1.0); g("%#.3g", 100.0); g("%G", 1e-10);
  g("%e", 0.0); g("%e", 123.456); g("%.3e", 0.125); g("%12.4e", 0.21);
  g("%-12.4e|", -0.21); g("%E", 1e100); g("%.0e", 12345.0); g("%#.0e", 12345.0);
  g("%f", 0.1); g("%.2f", 0.125); g("%.2f", 0.375); g("%.0f", 0.5); g("%.0f", 1.5);
  g("%.0f", 2.5); g("%#.0f", 3.0); g("%10.3f", 0.09); g("%010.3f", -0.09);
  g("%+.3f", 0.09); g("% .3f", 0.09); g("%+g", -0.0); g("%f", 1e20); g("%8.3lf", 2.0);
  g("%g", INFINITY); g("%g", -INFINITY); g("%08.2f", INFINITY); g("%E", NAN);
  g("x=%g;", 2.0); g("%g%%", 50.0);
  i("%lld", 0); i("%lld", -42); i("%lli", 7); i("%5lld", 3); i("%-5lld|", 3);
  i("%05lld", -3); i("%+lld", 0); i("% lld", 5); i("%.3lld", 7); i("%08.3lld", 7);
  i("%.0lld", 0); i("%lld", 9007199254740993LL); i("%lld", -9223372036854775807LL - 1);
  return 0;
}
