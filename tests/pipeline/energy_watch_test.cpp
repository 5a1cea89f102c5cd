// The stability guard's energy rule on synthetic velocity signals (energy_watch.hpp): an
// oscillation that grows while the command holds still trips it, with the numbers of its run; the
// same growth under a command that moves, swings whose size wanders under a stream of commands, a
// decaying or steady oscillation, a single push, an arm sped up without swinging, and noise at
// rest do not.

#include "comply/pipeline/energy_watch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <vector>

namespace comply::pipeline {
namespace {

constexpr double kPeriodS = 1e-3;
constexpr double kInertia = 0.2;  // [kg m^2] each joint's weight
constexpr int kDof = 3;

/// Runs the watch for `seconds` on velocity(t) at joint 1 (the others at rest) and the command
/// input(t) (one value: the command changed when it did); the time [s] it tripped at, or a
/// negative number.
double tripTime(
    EnergyWatch& watch, double seconds, const std::function<double(double)>& velocity,
    const std::function<double(double)>& input = [](double) { return 0.0; }) {
  const std::vector<double> inertia(kDof, kInertia);
  watch.configure({}, inertia);
  double last_input = input(0.0);
  for (int k = 0; k * kPeriodS < seconds; ++k) {
    const double t = k * kPeriodS;
    const double dq[kDof] = {0.0, velocity(t), 0.0};
    const double now = input(t);
    const bool changed = now != last_input;
    last_input = now;
    if (watch.update(dq, changed, kPeriodS)) {
      return t;
    }
  }
  return -1.0;
}

/// An 8 Hz oscillation whose energy grows e^(rate t) from `start_j`.
std::function<double(double)> oscillation(double start_j, double energy_rate_per_s) {
  const double amplitude = std::sqrt(2.0 * start_j / kInertia);
  return [=](double t) {
    return amplitude * std::exp(0.5 * energy_rate_per_s * t) * std::sin(2.0 * M_PI * 8.0 * t);
  };
}

TEST(EnergyWatch, AnOscillationGrowingUnderASteadyCommandTrips) {
  EnergyWatch watch;
  // Energy x2.7 per second from 0.02 J: past 0.05 J, and 4 x the run's start, after about 1.5 s.
  const double t = tripTime(watch, 5.0, oscillation(0.02, 1.0));
  ASSERT_GT(t, 0.0) << "never tripped";
  EXPECT_GT(t, 1.25);
  EXPECT_LT(t, 2.0);
  const EnergyWatch::Run& run = watch.run();
  EXPECT_EQ(run.joint, 1);
  EXPECT_GE(run.to_j, 4.0 * run.from_j);
  EXPECT_GT(run.to_j, 0.05);
  EXPECT_NEAR(run.to_j, 0.02 * std::exp(t), 0.25 * run.to_j) << "the last window's peak";
}

TEST(EnergyWatch, AFastRunawayTripsAfterThreeGrowingWindows) {
  EnergyWatch watch;
  // Energy x e^20 per second from a tiny disturbance, 0.05 J at about 0.69 s: the windows ending
  // at 0.5, 0.75 and 1.0 s rise over the one before (the first has none), and the third trips.
  const double t = tripTime(watch, 3.0, oscillation(5e-8, 20.0));
  ASSERT_GT(t, 0.0);
  EXPECT_NEAR(t, 1.0, 2e-3);
  EXPECT_NEAR(watch.run().duration_s, 0.75, 1e-9);
}

TEST(EnergyWatch, APushThatSwingsUpWithinOneWindowDoesNotTrip) {
  EnergyWatch watch;
  // An arm at rest, pushed at 1.1 s: a swing that rises from nothing to 0.5 J within one window
  // and then decays. What an admittance arm pushed by a hand does.
  EXPECT_LT(tripTime(watch, 5.0,
                     [](double t) {
                       if (t < 1.1) {
                         return 1e-4 * std::sin(2.0 * M_PI * 8.0 * t);
                       }
                       const double since = t - 1.1;
                       return 2.2 * std::min(1.0, since / 0.1) * std::exp(-3.0 * since) *
                              std::sin(2.0 * M_PI * 8.0 * since);
                     }),
            0.0);
}

TEST(EnergyWatch, TheSameGrowthUnderACommandThatMovesDoesNotTrip) {
  EnergyWatch watch;
  const auto grow = oscillation(0.02, 1.0);
  // A reference swinging with the arm: what a sender commanding ever larger swings does.
  EXPECT_LT(tripTime(watch, 5.0, grow, [&](double t) { return 0.1 * grow(t); }), 0.0);
}

/// Swings whose size jumps at random every window, as an arm under a random stream of poses swings
/// (the soak's stream, where a rule that judged the stream by how it varied tripped).
std::function<double(double)> wanderingSwing(unsigned seed) {
  auto random = std::make_shared<std::mt19937>(seed);
  auto amplitude = std::make_shared<double>(0.5);
  auto window = std::make_shared<int>(-1);
  return [=](double t) {
    if (const int now = static_cast<int>(t / 0.25); now != *window) {
      *window = now;
      *amplitude = std::uniform_real_distribution<double>(0.05, 2.0)(*random);
    }
    return *amplitude * std::sin(2.0 * M_PI * 8.0 * t);
  };
}

TEST(EnergyWatch, SwingsOfRandomSizeTripUnderAHeldCommandButNotUnderAStream) {
  // Under a held command, three rising windows (energy x4 and more) among random swing sizes are
  // taken for the loop's own: the rule's known limit (an arm shaken by hand). The same swings
  // under a stream of commands (a new one every 5 ms, as the soak's senders) never trip: only a
  // command that holds still makes the energy the loop's.
  EnergyWatch watch;
  const double held = tripTime(watch, 600.0, wanderingSwing(3));
  ASSERT_GT(held, 0.0) << "the random sizes never rose three windows in a row: pick another seed";
  EXPECT_LT(
      tripTime(watch, 600.0, wanderingSwing(3), [](double t) { return std::floor(t / 0.005); }),
      0.0);
}

TEST(EnergyWatch, DecayingAndSteadyOscillationsDoNotTrip) {
  EnergyWatch watch;
  EXPECT_LT(tripTime(watch, 5.0, oscillation(1.0, -2.0)), 0.0);
  EXPECT_LT(tripTime(watch, 5.0, oscillation(1.0, 0.0)), 0.0);
}

TEST(EnergyWatch, APushAndAnArmSpedUpWithoutSwingingDoNotTrip) {
  EnergyWatch watch;
  // A push: 1 J at once, then a decaying swing.
  EXPECT_LT(tripTime(watch, 5.0,
                     [&](double t) {
                       return t < 1.0 ? 0.0
                                      : 3.0 * std::exp(-2.0 * (t - 1.0)) *
                                            std::cos(2.0 * M_PI * 8.0 * (t - 1.0));
                     }),
            0.0);
  // Hand guiding that speeds up steadily, energy x2.7 per second, one way.
  EXPECT_LT(tripTime(watch, 5.0, [](double t) { return 0.5 * std::exp(0.5 * t); }), 0.0);
}

TEST(EnergyWatch, NoiseAtRestDoesNotTrip) {
  EnergyWatch watch;
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  EXPECT_LT(tripTime(watch, 20.0, [&](double) { return noise(random); }), 0.0);
}

TEST(EnergyWatch, OffItNeverTrips) {
  EnergyWatch watch;
  const std::vector<double> inertia(kDof, kInertia);
  watch.configure({.window_s = 0.0}, inertia);
  EXPECT_FALSE(watch.enabled());
  const auto grow = oscillation(0.02, 5.0);
  for (int k = 0; k < 5000; ++k) {
    const double dq[kDof] = {0.0, grow(k * kPeriodS), 0.0};
    ASSERT_FALSE(watch.update(dq, false, kPeriodS));
  }
}

}  // namespace
}  // namespace comply::pipeline
