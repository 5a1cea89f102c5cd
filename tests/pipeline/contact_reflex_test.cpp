// The reflex stage on its own (contact_reflex.hpp): the debounce (one sample, a run cut short, a
// run as long as the debounce), the thresholds as an ellipsoid per task axis in the task frame,
// a command's 0 entries standing for the file's, a cycle without an estimate, and the retreat's
// reference.

#include "comply/pipeline/contact_reflex.hpp"

#include <gtest/gtest.h>

#include <string>

namespace comply::pipeline {
namespace {

constexpr double kPeriod = 0.001;

ReflexConfig fileConfig() {
  ReflexConfig config;
  config.enabled = true;
  config.force_n = 20.0;
  config.torque_nm = 5.0;
  config.debounce_s = 0.005;
  return config;
}

Vector6d force(double x, double y, double z) {
  Vector6d wrench = Vector6d::Zero();
  wrench.head<3>() << x, y, z;
  return wrench;
}

ReflexThresholds uniform(double force_n, double torque_nm) {
  return {Eigen::Vector3d::Constant(force_n), Eigen::Vector3d::Constant(torque_nm)};
}

/// Cycles `wrench` until the reflex trips (or `limit` cycles); the cycle it tripped in, 1-based,
/// or 0.
int cyclesToTrip(ContactReflex& reflex, const Vector6d& wrench, const ReflexThresholds& thresholds,
                 int limit = 100, const Eigen::Quaterniond& task = Eigen::Quaterniond::Identity()) {
  for (int cycle = 1; cycle <= limit; ++cycle) {
    if (reflex.check(&wrench, task, thresholds, kPeriod) == ContactReflex::Check::kTripped) {
      return cycle;
    }
  }
  return 0;
}

TEST(ContactReflex, OneSampleAboveDoesNotTripAndARunAsLongAsTheDebounceDoes) {
  ContactReflex reflex(fileConfig());
  const ReflexThresholds thresholds = uniform(20.0, 5.0);
  const Vector6d push = force(0.0, 30.0, 0.0);
  const Vector6d quiet = force(0.0, 5.0, 0.0);
  // One noisy sample, then quiet: never.
  EXPECT_EQ(reflex.check(&push, Eigen::Quaterniond::Identity(), thresholds, kPeriod),
            ContactReflex::Check::kArmed);
  EXPECT_EQ(cyclesToTrip(reflex, quiet, thresholds), 0);
  // Five samples above (0 to 4 ms: 4 ms above), a quiet one ends the run; the next run starts
  // from nothing.
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(reflex.check(&push, Eigen::Quaterniond::Identity(), thresholds, kPeriod),
              ContactReflex::Check::kArmed);
  }
  EXPECT_EQ(reflex.check(&quiet, Eigen::Quaterniond::Identity(), thresholds, kPeriod),
            ContactReflex::Check::kArmed);
  EXPECT_FALSE(reflex.tripped());
  // Above for 5 ms: the sixth sample of a run (the first starts the count at 0).
  EXPECT_EQ(cyclesToTrip(reflex, push, thresholds), 6);
  EXPECT_TRUE(reflex.tripped());
  EXPECT_TRUE(reflex.latched());  // hold, the default
  EXPECT_EQ(reflex.wrench(), push);

  // Without a debounce, the first sample above trips.
  ReflexConfig eager = fileConfig();
  eager.debounce_s = 0.0;
  ContactReflex at_once(eager);
  EXPECT_EQ(cyclesToTrip(at_once, push, thresholds), 1);
  // reset() arms it again.
  at_once.reset();
  EXPECT_FALSE(at_once.tripped());
  EXPECT_EQ(at_once.wrench(), Vector6d::Zero());
}

TEST(ContactReflex, EqualThresholdsTripOnTheNormInEveryDirection) {
  ReflexConfig config = fileConfig();
  config.debounce_s = 0.0;
  ContactReflex reflex(config);
  const ReflexThresholds thresholds = uniform(20.0, 5.0);
  // 21 N between three axes (12.1 N each) trips; 19 N along one does not.
  const double each = 21.0 / std::sqrt(3.0);
  EXPECT_EQ(cyclesToTrip(reflex, force(each, -each, each), thresholds, 1), 1);
  reflex.reset();
  EXPECT_EQ(cyclesToTrip(reflex, force(0.0, 0.0, -19.0), thresholds, 1), 0);
  // The torque on its own.
  Vector6d twist = Vector6d::Zero();
  twist.tail<3>() << 3.0, 3.0, 3.0;  // 5.2 N m
  EXPECT_EQ(cyclesToTrip(reflex, twist, thresholds, 1), 1);
  EXPECT_NE(std::string(reflex.detail()).find("contact torque (3, 3, 3) N m"), std::string::npos)
      << reflex.detail();
}

TEST(ContactReflex, ARaisedAxisLetsAPushAlongItThroughAndNotOneAcrossIt) {
  ReflexConfig config = fileConfig();
  config.debounce_s = 0.0;
  ContactReflex reflex(config);
  // A command raised task z to 60 N: 45 N along z passes, 25 N along x trips, and so does
  // 45 N between y and z: (31.8 / 20)^2 + (31.8 / 60)^2 > 1.
  const ReflexThresholds raised{Eigen::Vector3d(20.0, 20.0, 60.0), Eigen::Vector3d::Constant(5.0)};
  EXPECT_EQ(cyclesToTrip(reflex, force(0.0, 0.0, 45.0), raised, 10), 0);
  EXPECT_EQ(cyclesToTrip(reflex, force(25.0, 0.0, 0.0), raised, 1), 1);
  reflex.reset();
  const double half = 45.0 / std::sqrt(2.0);
  EXPECT_EQ(cyclesToTrip(reflex, force(0.0, half, half), raised, 1), 1);
  EXPECT_NE(std::string(reflex.detail()).find("thresholds (20, 20, 60) N"), std::string::npos)
      << reflex.detail();
  EXPECT_NE(std::string(reflex.detail()).find("reflex.force_n, or the command's reflex_force"),
            std::string::npos)
      << reflex.detail();
}

TEST(ContactReflex, TheThresholdsAreTheTaskFramesAxes) {
  ReflexConfig config = fileConfig();
  config.debounce_s = 0.0;
  ContactReflex reflex(config);
  const ReflexThresholds raised{Eigen::Vector3d(20.0, 20.0, 60.0), Eigen::Vector3d::Constant(5.0)};
  // The task frame turned a quarter about base x: its z is base -y. 45 N along base -y is along
  // task z (raised): it passes; in the base frame's axes it would trip.
  const Eigen::Quaterniond task(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()));
  const Vector6d push = force(0.0, -45.0, 0.0);
  EXPECT_EQ(cyclesToTrip(reflex, push, raised, 10, task), 0);
  EXPECT_EQ(cyclesToTrip(reflex, push, raised, 1), 1);
  // What it reports is in the task frame of the trip.
  reflex.reset();
  const Vector6d across = force(30.0, 0.0, 0.0);  // task x
  EXPECT_EQ(cyclesToTrip(reflex, across, raised, 1, task), 1);
  EXPECT_NEAR(reflex.wrench()[0], 30.0, 1e-12);
}

TEST(ContactReflex, EqualThresholdsTripTheSameInEveryFrameAndReportInTheTaskFrame) {
  ReflexConfig config = fileConfig();
  config.debounce_s = 0.0;
  ContactReflex reflex(config);
  const ReflexThresholds thresholds = uniform(20.0, 5.0);
  const Eigen::Quaterniond task(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()));
  // |F| = 19.9 N along a diagonal: inside the sphere whatever the frame.
  const Vector6d inside = force(11.489, -11.489, 11.489);
  EXPECT_EQ(cyclesToTrip(reflex, inside, thresholds, 5, task), 0);
  const Vector6d push = force(0.0, -25.0, 0.0);  // base -y is task z
  EXPECT_EQ(cyclesToTrip(reflex, push, thresholds, 1, task), 1);
  EXPECT_NEAR(reflex.wrench()[0], 0.0, 1e-12);
  EXPECT_NEAR(reflex.wrench()[1], 0.0, 1e-12);
  EXPECT_NEAR(reflex.wrench()[2], 25.0, 1e-12);
}

TEST(ContactReflex, ACommandsZeroEntriesAreTheFilesThresholds) {
  ContactReflex reflex(fileConfig());
  const double force_entries[3] = {0.0, 35.0, 0.0};
  const double torque_entries[3] = {2.0, 0.0, 0.0};
  const ReflexThresholds thresholds = reflex.thresholds(force_entries, torque_entries);
  EXPECT_EQ(thresholds.force_n, Eigen::Vector3d(20.0, 35.0, 20.0));
  EXPECT_EQ(thresholds.torque_nm, Eigen::Vector3d(2.0, 5.0, 5.0));
  // The state reports what the last check used.
  const Vector6d quiet = Vector6d::Zero();
  (void)reflex.check(&quiet, Eigen::Quaterniond::Identity(), thresholds, kPeriod);
  EXPECT_EQ(reflex.inForce().force_n, thresholds.force_n);
}

TEST(ContactReflex, CyclesWithoutAnEstimateNeitherCountNorEndARunAndFaultAfterATenthOfASecond) {
  ContactReflex reflex(fileConfig());
  const ReflexThresholds thresholds = uniform(20.0, 5.0);
  const Vector6d push = force(30.0, 0.0, 0.0);
  const Eigen::Quaterniond base = Eigen::Quaterniond::Identity();
  // Three samples above (2 ms), ten cycles without an estimate, two more above (4 ms): not yet;
  // the next (5 ms) trips.
  for (int i = 0; i < 3; ++i) {
    ASSERT_EQ(reflex.check(&push, base, thresholds, kPeriod), ContactReflex::Check::kArmed);
  }
  for (int i = 0; i < 10; ++i) {
    ASSERT_EQ(reflex.check(nullptr, base, thresholds, kPeriod), ContactReflex::Check::kArmed);
  }
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(reflex.check(&push, base, thresholds, kPeriod), ContactReflex::Check::kArmed);
  }
  EXPECT_EQ(reflex.check(&push, base, thresholds, kPeriod), ContactReflex::Check::kTripped);

  // No estimate at all: armed for 0.1 s, then it says it cannot act.
  ContactReflex blind(fileConfig());
  int cycles = 0;
  ContactReflex::Check check = ContactReflex::Check::kArmed;
  while (check == ContactReflex::Check::kArmed && cycles < 1000) {
    check = blind.check(nullptr, base, thresholds, kPeriod);
    ++cycles;
  }
  EXPECT_EQ(check, ContactReflex::Check::kNoEstimate);
  EXPECT_EQ(cycles, 100);
  EXPECT_NE(std::string(blind.detail()).find("observer.enabled"), std::string::npos)
      << blind.detail();
  EXPECT_FALSE(blind.tripped());
}

TEST(ContactReflex, ARetreatBacksOffAlongThePushAtItsSpeedThenHolds) {
  ReflexConfig config = fileConfig();
  config.reaction = ReflexReaction::kRetreat;
  config.debounce_s = 0.0;
  config.retreat_m = 0.05;
  config.retreat_speed_m_per_s = 0.1;
  ContactReflex reflex(config);
  ASSERT_EQ(cyclesToTrip(reflex, force(0.0, 18.0, 24.0), uniform(20.0, 5.0), 1), 1);
  EXPECT_TRUE(reflex.latched());
  const Eigen::Vector3d start(0.3, 0.0, 0.5);
  reflex.startRetreat(start);
  const Eigen::Vector3d along(0.0, 0.6, 0.8);  // the push's direction
  Eigen::Vector3d position;
  Eigen::Vector3d velocity;
  reflex.retreat(0.0, position, velocity);
  EXPECT_EQ(position, start);
  reflex.retreat(0.2, position, velocity);
  EXPECT_LT((position - (start + 0.02 * along)).norm(), 1e-12);
  EXPECT_LT((velocity - 0.1 * along).norm(), 1e-12);
  reflex.retreat(0.6, position, velocity);  // 0.06 m at 0.1 m/s: it stopped at 0.05
  EXPECT_LT((position - (start + 0.05 * along)).norm(), 1e-12);
  EXPECT_EQ(velocity, Eigen::Vector3d::Zero());

  // Tripped by a torque alone: no direction to back off along, it holds where it was.
  reflex.reset();
  Vector6d twist = Vector6d::Zero();
  twist[5] = 8.0;
  ASSERT_EQ(cyclesToTrip(reflex, twist, uniform(20.0, 5.0), 1), 1);
  reflex.startRetreat(start);
  reflex.retreat(0.3, position, velocity);
  EXPECT_EQ(position, start);
  EXPECT_EQ(velocity, Eigen::Vector3d::Zero());

  // A fault reaction trips without latching: FAULT holds the arm instead.
  config.reaction = ReflexReaction::kFault;
  ContactReflex faulting(config);
  ASSERT_EQ(cyclesToTrip(faulting, force(30.0, 0.0, 0.0), uniform(20.0, 5.0), 1), 1);
  EXPECT_TRUE(faulting.tripped());
  EXPECT_FALSE(faulting.latched());
}

}  // namespace
}  // namespace comply::pipeline
