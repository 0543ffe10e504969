// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// The per-insertion phase clock (engine/src/support/phase_clock.hpp): its ticks, converted at the
// rate it measured, give the seconds that steady_clock gives for the same interval, and an interval
// read backwards counts zero. The bounds are a factor of 2 around the steady clock's interval: this
// checks the conversion (a wrong rate is off by a factor of the clock's frequency in GHz, or more),
// not its precision, which a 1 ms calibration on a loaded 2-core machine does not promise (the
// earlier 10 % bounds depended on the scheduler).
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "support/phase_clock.hpp"

namespace dtlab::test {
namespace {

using engine::PhaseClock;

TEST(PhaseClock, TicksConvertToTheSecondsOfTheSteadyClock) {
  using Clock = std::chrono::steady_clock;
  for (const int milliseconds : {20, 60}) {
    const Clock::time_point wall_start = Clock::now();
    const PhaseClock::Ticks start = PhaseClock::now();
    std::this_thread::sleep_for(std::chrono::milliseconds(milliseconds));
    const PhaseClock::Ticks end = PhaseClock::now();
    const double wall = std::chrono::duration<double>(Clock::now() - wall_start).count();
    const double measured = PhaseClock::seconds(start, end);
    EXPECT_GE(measured, 0.5 * milliseconds / 1000.0) << milliseconds;
    EXPECT_LE(measured, 2.0 * wall + 1e-3) << milliseconds;
    EXPECT_EQ(PhaseClock::seconds(end, start), 0.0);
  }
}

}  // namespace
}  // namespace dtlab::test
