// The contact-speed stage's sweep on the simulated FR3 (label long: about a minute on 2 cores): the
// probe driven into a hand's spring (75 N/mm, spring_contact.hpp) at 0.05 to 1 m/s from three
// poses, with the stage on (hands, quasi-static: 140 N) and off. On, no run's peak passes 140 N;
// off, every run from kExceedsFromMPerS to kExceedsUpToMPerS passes it. Apart, a reference that
// runs on 20 mm through the contact at speed: the stage still brings the probe in below its
// v_max, and the peaks say what the law's push behind it adds (docs/safety.md). The runs go to
// $TMPDIR/comply_contact_speed_sweep/sweep.csv, which scripts/plot_contact_speed.py draws
// (docs/images/contact_speed_sweep.png), and to the test's XML properties.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "spring_contact.hpp"

namespace comply::testing {
namespace {

constexpr double kSpeeds[] = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
// Without the stage, from this commanded speed on every pose's spring passes 140 N (at 0.3 m/s
// each does too, home by 3 N: the bound asserted keeps a margin).
constexpr double kExceedsFromMPerS = 0.4;
// Past it the reference runs far ahead of what the joints' bound lets the arm follow (0.8 m/s),
// stops at the face, and how fast the probe arrives depends on how the law catches up: at 1 m/s
// the tilted pose came in slowed and stayed at 61 N.
constexpr double kExceedsUpToMPerS = 0.9;
constexpr double kThroughSpeeds[] = {0.3, 0.6, 1.0};

void writeRow(std::ofstream& csv, const std::string& pose, const char* reference, bool governed,
              const SpringRun& run) {
  csv << pose << "," << reference << "," << governed << "," << run.commanded_m_per_s << ","
      << run.fastest_m_per_s << "," << run.contact_speed_m_per_s << "," << run.peak_force_n << ","
      << run.settled_force_n << "," << run.limit_m_per_s << "," << run.mass_kg << ","
      << run.stage_cycles << "," << run.rate_limit_hits << "," << run.brake_onsets << "\n";
}

TEST(ContactSpeedSweep, NoGovernedRunPassesTheHandsLimitAndEveryFastUngovernedOneDoes) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / "comply_contact_speed_sweep";
  std::filesystem::create_directories(folder);
  std::ofstream csv(folder / "sweep.csv");
  csv << "pose,reference,governed,commanded_m_per_s,fastest_m_per_s,contact_speed_m_per_s,"
         "peak_force_n,settled_force_n,limit_m_per_s,mass_kg,stage_cycles,rate_limit_hits,"
         "brake_onsets\n";
  std::ostringstream table;
  table << std::fixed << std::setprecision(2);
  double worst_governed = 0.0;
  int runs = 0;
  for (const ArmPose& pose : springPoses()) {
    const SpringScene scene = springScene(pose, folder / pose.name);
    table << pose.name << ": mu along the tool axis " << scene.axis_mass_kg << " kg\n";
    for (const double speed : kSpeeds) {
      for (const bool governed : {false, true}) {
        const SpringRun run = driveIntoSpring(scene, springConfig(governed), speed);
        ++runs;
        const std::string what = pose.name + (governed ? " on " : " off ") + std::to_string(speed);
        EXPECT_TRUE(run.touched) << what;
        EXPECT_FALSE(run.faulted) << what;
        if (governed) {
          EXPECT_LT(run.peak_force_n, kHandsQuasiStaticLimitN) << what;
          worst_governed = std::max(worst_governed, run.peak_force_n);
        } else if (speed >= kExceedsFromMPerS && speed <= kExceedsUpToMPerS + 1e-9) {
          EXPECT_GT(run.peak_force_n, kHandsQuasiStaticLimitN) << what;
        }
        writeRow(csv, pose.name, "stop", governed, run);
        table << pose.name << (governed ? " on  " : " off ") << speed << " m/s: fastest "
              << run.fastest_m_per_s << " m/s, touch at " << run.contact_speed_m_per_s
              << " m/s, peak " << run.peak_force_n << " N, v_max " << run.limit_m_per_s
              << " m/s, mu " << run.mass_kg << " kg, stage " << run.stage_cycles
              << " cycles, rate limit " << run.rate_limit_hits << ", brake onsets "
              << run.brake_onsets << "\n";
      }
    }
    for (const double speed : kThroughSpeeds) {
      const SpringRun run = driveIntoSpring(scene, springConfig(true), speed,
                                            {.past_surface_m = kThroughSurfaceM, .through = true});
      ++runs;
      EXPECT_TRUE(run.touched);
      EXPECT_LT(run.contact_speed_m_per_s, run.limit_m_per_s) << pose.name << " through " << speed;
      writeRow(csv, pose.name, "through", true, run);
      table << pose.name << " through " << speed << " m/s: fastest " << run.fastest_m_per_s
            << " m/s, touch at " << run.contact_speed_m_per_s << " m/s (v_max " << run.limit_m_per_s
            << "), peak " << run.peak_force_n << " N\n";
    }
  }
  EXPECT_EQ(runs, 75);
  std::cout << table.str() << "sweep: " << (folder / "sweep.csv").string() << "\n";
  RecordProperty("largest_governed_peak_n", std::to_string(worst_governed));
}

}  // namespace
}  // namespace comply::testing
