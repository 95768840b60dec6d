// The machine's limits for the roofline estimate of docs/performance.md:
//   Triad      a[i] = b[i] + s c[i] over arrays far larger than the caches (STREAM's triad):
//              bytes_per_second counts 24 bytes per element (read b, c; write a; no
//              write-allocate counted, as STREAM does).
//   PeakFlops  independent multiply-add chains in registers: flops per second of one core,
//              for the build's baseline ISA (what the step is compiled for) and, when the CPU
//              has them, AVX2 + FMA (what -march=native could use).
//   build/bin/roofline_bench --benchmark_format=json
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

namespace {

void BM_Triad(benchmark::State& bs) {
  const size_t n = size_t(bs.range(0));
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  for (auto _ : bs) {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    for (size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::ClobberMemory();
  }
  bs.SetBytesProcessed(int64_t(bs.iterations()) * int64_t(n) * 24);
}
// 3 x 256 MiB: far beyond any cache
BENCHMARK(BM_Triad)->Arg(1 << 25)->Unit(benchmark::kMillisecond)->UseRealTime();

// 64 independent chains x = x m + a (2 flops each per iteration), vectorized by the compiler
__attribute__((noinline)) double chains(long iters, double m, double a) {
  double x[64];
  for (int i = 0; i < 64; ++i) x[i] = 1.0 + 1e-9 * i;
  for (long k = 0; k < iters; ++k)
    for (int i = 0; i < 64; ++i) x[i] = x[i] * m + a;
  double s = 0;
  for (int i = 0; i < 64; ++i) s += x[i];
  return s;
}

void BM_PeakFlopsBaseline(benchmark::State& bs) {
  const long iters = 1 << 16;
  for (auto _ : bs) {
    volatile double m = 0.999999999, a = 1e-9;  // not folded or hoisted
    benchmark::DoNotOptimize(chains(iters, m, a));
  }
  bs.counters["flops"] = benchmark::Counter(double(bs.iterations()) * iters * 64 * 2,
                                            benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PeakFlopsBaseline);

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2,fma"))) double chains_fma(long iters) {
  double x[64];
  for (int i = 0; i < 64; ++i) x[i] = 1.0 + 1e-9 * i;
  const double m = 0.999999999, a = 1e-9;
  for (long k = 0; k < iters; ++k)
    for (int i = 0; i < 64; ++i) x[i] = __builtin_fma(x[i], m, a);
  double s = 0;
  for (int i = 0; i < 64; ++i) s += x[i];
  return s;
}

void BM_PeakFlopsAvx2Fma(benchmark::State& bs) {
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma"))
    return bs.SkipWithError("no AVX2/FMA");
  const long iters = 1 << 16;
  for (auto _ : bs) {
    long it = iters;
    benchmark::DoNotOptimize(it);
    benchmark::DoNotOptimize(chains_fma(it));
  }
  bs.counters["flops"] = benchmark::Counter(double(bs.iterations()) * iters * 64 * 2,
                                            benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PeakFlopsAvx2Fma);
#endif

}  // namespace

BENCHMARK_MAIN();
