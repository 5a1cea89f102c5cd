// Joint impedance that misbehaves on purpose, from cycle `at_step` on (plugin_parameters):
//   fault: 0 none, 1 NaN torque, 2 saturate (1e6 N m on every joint), 3 overrun (sleep
//   overrun_ms per step), 4 crash (a write through a null pointer), 5 hang (never returns),
//   6 abort(), 7 huge (1e300 N m on every joint: finite, so only the effort limit stops it).
// Each fault has one defined end, which tests/faults/fault_injection_test.sh checks and the
// README's safety section states.

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <thread>

#include "comply/plugin/controller.hpp"

namespace comply::tests {
namespace {

enum class Fault { kNone, kNan, kSaturate, kOverrun, kCrash, kHang, kAbort, kHuge };

class FaultInjector final : public JointController {
 public:
  void configure(int dof, const plugin::Parameters& parameters) override {
    dof_ = dof;
    fault_ = static_cast<Fault>(static_cast<int>(parameters.number("fault", 0.0)));
    at_step_ = static_cast<long>(parameters.number("at_step", 100.0));
    overrun_ms_ = parameters.number("overrun_ms", 5.0);
  }

  comply_status step(const comply_input& input, const comply_joint_command& command,
                     comply_output& output) noexcept override {
    for (int i = 0; i < dof_; ++i) {
      output.torque[i] = command.stiffness[i] * (command.position[i] - input.position[i]) +
                         command.damping[i] * (command.velocity[i] - input.velocity[i]);
    }
    if (++steps_ < at_step_) {
      return COMPLY_OK;
    }
    switch (fault_) {
      case Fault::kNan:
        output.torque[0] = std::numeric_limits<double>::quiet_NaN();
        break;
      case Fault::kSaturate:
      case Fault::kHuge:
        for (int i = 0; i < dof_; ++i) {
          output.torque[i] = fault_ == Fault::kHuge ? 1e300 : 1e6;
        }
        break;
      case Fault::kOverrun:
        std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(overrun_ms_));
        break;
      case Fault::kCrash: {
        volatile double* nowhere = nullptr;
        *nowhere = 1.0;
        break;
      }
      case Fault::kHang:
        for (volatile bool forever = true; forever;) {
        }
        break;
      case Fault::kAbort:
        std::abort();
      case Fault::kNone:
        break;
    }
    return COMPLY_OK;
  }

 private:
  int dof_ = 0;
  Fault fault_ = Fault::kNone;
  long at_step_ = 100;
  long steps_ = 0;
  double overrun_ms_ = 5.0;
};

}  // namespace
}  // namespace comply::tests

COMPLY_EXPORT_CONTROLLER(comply::tests::FaultInjector, "fault_injector")
