#pragma once
// The clock of the per-insertion phase times (seconds.location, .subdivision, .legalization):
// three reads an insertion. Read through std::chrono::steady_clock they cost a visible part of a
// sequential walk's run (docs/performance.md, "Measured choices"), so on x86-64 they read the
// time-stamp counter instead, and the ticks are converted to seconds at its rate, measured once
// per process against steady_clock. Elsewhere they read steady_clock.
//
// What this assumes: a TSC that ticks at a constant rate whatever the core's frequency and that
// agrees between cores (every x86-64 CPU of the last fifteen years: Linux's "constant_tsc" and
// "nonstop_tsc"). A difference that comes out negative (a thread moved to a core whose counter
// is behind) counts as zero. The phase times are a breakdown of the run; `seconds.total` is
// always steady_clock's.
#include <chrono>
#include <cstdint>

#if defined(__x86_64__)
#include <x86intrin.h>
#endif

namespace dtlab::engine {

class PhaseClock {
 public:
  using Ticks = std::uint64_t;

  static Ticks now() {
#if defined(__x86_64__)
    return __rdtsc();
#else
    return static_cast<Ticks>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                  std::chrono::steady_clock::now().time_since_epoch())
                                  .count());
#endif
  }

  // Measures the rate now if it was not measured yet (a millisecond, once per process): before
  // the first phase, so that the measurement is in none.
  static void calibrate() {
    (void)seconds_per_tick();
  }

  // Seconds from `start` to `end`, two reads of now() in this order.
  static double seconds(Ticks start, Ticks end) {
    return end > start ? static_cast<double>(end - start) * seconds_per_tick() : 0.0;
  }

 private:
  // The rate, measured at the first use over at least a millisecond of steady_clock (a few
  // nanoseconds of error at each end: 1e-5 of the rate). One thread measures; the others wait
  // for it (a function-local static).
  static double seconds_per_tick() {
#if defined(__x86_64__)
    static const double rate = [] {
      using Clock = std::chrono::steady_clock;
      const Clock::time_point wall_start = Clock::now();
      const Ticks tick_start = now();
      Clock::time_point wall_end = wall_start;
      while (wall_end - wall_start < std::chrono::milliseconds(1)) wall_end = Clock::now();
      const Ticks tick_end = now();
      const double elapsed = std::chrono::duration<double>(wall_end - wall_start).count();
      return tick_end > tick_start ? elapsed / static_cast<double>(tick_end - tick_start) : 0.0;
    }();
    return rate;
#else
    return 1e-9;
#endif
  }
};

}  // namespace dtlab::engine
