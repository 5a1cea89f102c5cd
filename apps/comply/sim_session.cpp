#include "sim_session.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <thread>

#include "comply/pipeline/wrapper.hpp"
#include "comply/plugin/loader.hpp"
#include "comply/schema/schema.hpp"
#include "comply/sim/image.hpp"
#include "comply/sim/renderer.hpp"
#include "comply/sim/sim_error.hpp"
#include "comply/sim/viewer.hpp"
#include "progress_bar.hpp"

namespace comply::app {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kSettlePositionM = 0.001;
constexpr double kSettleOrientationRad = 0.5 * M_PI / 180.0;
constexpr double kSettleJointRad = 0.001;
constexpr std::size_t kMaxMessages = 8;
constexpr double kViewerPeriodS = 1.0 / 60.0;

/// The motion reference of a task at one time: pose (or joint position) and its rate.
struct Reference {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Vector6d twist = Vector6d::Zero();
  JointVector joint_position;
  JointVector joint_velocity;
};

/// Waypoint targets resolved against the start: absolute positions, orientations carried over.
class Trajectory {
 public:
  Trajectory(const TaskFile& task, const Reference& start) : start_(start) {
    Reference previous = start;
    for (const Waypoint& waypoint : task.waypoints) {
      Reference target = previous;
      target.twist.setZero();
      if (start.joint_position.size() > 0) {
        target.joint_velocity.setZero();
        if (waypoint.position) {
          target.joint_position = Eigen::Map<const Eigen::VectorXd>(
              waypoint.position->data(), static_cast<Eigen::Index>(waypoint.position->size()));
        } else if (waypoint.position_offset) {
          target.joint_position = start.joint_position +
                                  Eigen::Map<const Eigen::VectorXd>(
                                      waypoint.position_offset->data(),
                                      static_cast<Eigen::Index>(waypoint.position_offset->size()));
        }
      } else {
        if (waypoint.position) {
          target.position = Eigen::Vector3d((*waypoint.position)[0], (*waypoint.position)[1],
                                            (*waypoint.position)[2]);
        } else if (waypoint.position_offset) {
          target.position = start.position + Eigen::Vector3d((*waypoint.position_offset)[0],
                                                             (*waypoint.position_offset)[1],
                                                             (*waypoint.position_offset)[2]);
        }
        if (waypoint.orientation) {
          const std::vector<double>& q = *waypoint.orientation;
          target.orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized();
        }
      }
      targets_.push_back(target);
      times_.push_back(waypoint.time_s);
      linear_.push_back(waypoint.interpolate == Interpolation::kLinear);
      previous = target;
    }
  }

  [[nodiscard]] Reference at(double t) const {
    std::size_t next = 0;
    while (next < times_.size() && times_[next] <= t) {
      ++next;
    }
    if (next == times_.size()) {
      return targets_.back();
    }
    const Reference& from = next == 0 ? start_ : targets_[next - 1];
    const double t0 = next == 0 ? 0.0 : times_[next - 1];
    const double span = times_[next] - t0;
    if (!linear_[next] || span <= 0.0) {
      Reference hold = from;
      hold.twist.setZero();
      if (hold.joint_velocity.size() > 0) {
        hold.joint_velocity.setZero();
      }
      return hold;
    }
    const Reference& to = targets_[next];
    const double s = (t - t0) / span;
    Reference out = to;
    if (from.joint_position.size() > 0) {
      out.joint_position = from.joint_position + s * (to.joint_position - from.joint_position);
      out.joint_velocity = (to.joint_position - from.joint_position) / span;
      return out;
    }
    out.position = from.position + s * (to.position - from.position);
    Eigen::Quaterniond goal = to.orientation;
    if (from.orientation.dot(goal) < 0.0) {
      goal.coeffs() = -goal.coeffs();  // shortest way round
    }
    out.orientation = from.orientation.slerp(s, goal);
    out.twist.head<3>() = (to.position - from.position) / span;
    // Constant angular velocity of the slerp, in the base frame.
    const Eigen::AngleAxisd delta(goal * from.orientation.conjugate());
    out.twist.tail<3>() = delta.axis() * delta.angle() / span;
    return out;
  }

  [[nodiscard]] double endTime() const { return times_.back(); }

 private:
  Reference start_;
  std::vector<Reference> targets_;
  std::vector<double> times_;
  std::vector<bool> linear_;
};

void setMotion(CartesianCommand& command, const Reference& reference) {
  command.position = reference.position;
  command.orientation = reference.orientation;
  command.twist = reference.twist;
}
void setMotion(JointCommand& command, const Reference& reference) {
  command.position = reference.joint_position;
  command.velocity = reference.joint_velocity;
}

Reference startReference(const CartesianCommand& seeded) {
  Reference start;
  start.position = seeded.position;
  start.orientation = seeded.orientation;
  return start;
}
Reference startReference(const JointCommand& seeded) {
  Reference start;
  start.joint_position = seeded.position;
  start.joint_velocity = JointVector::Zero(seeded.position.size());
  return start;
}

void addMessage(SimSummary& summary, const std::string& message, std::ostream* progress) {
  if (summary.messages.size() < kMaxMessages) {
    summary.messages.push_back(message);
    if (progress != nullptr) {
      *progress << "\ncomply sim: " << message << "\n";
    }
  }
}

/// Snapshots and the live view; both optional, both outside the control cycle.
class Pictures {
 public:
  Pictures(const SimRunOptions& options, const sim::SimulatedRobot& robot, SimSummary& summary)
      : options_(options), summary_(summary) {
    if (options.snapshots && !options.out_dir.empty()) {
      try {
        renderer_ = std::make_unique<sim::Renderer>(robot.mujocoModel(), options.image_width,
                                                    options.image_height);
      } catch (const sim::SimError& error) {
        addMessage(summary, std::string("snapshots skipped: ") + error.what(), options.progress);
      }
    }
    if (options.view) {
      viewer_ =
          std::make_unique<sim::Viewer>(robot.mujocoModel(), "comply sim", options.task.camera);
    }
  }

  void snapshot(const sim::SimulatedRobot& robot, const std::string& name) {
    if (!renderer_) {
      return;
    }
    const std::filesystem::path file = options_.out_dir / (name + ".png");
    sim::writePng(renderer_->render(robot.mujocoData(), options_.task.camera), file);
    summary_.files.push_back(file);
  }

  /// False once the user closed the window.
  bool show(const sim::SimulatedRobot& robot, double t) {
    if (!viewer_ || t < next_view_s_) {
      return true;
    }
    next_view_s_ = t + kViewerPeriodS;
    return viewer_->show(robot.mujocoData());
  }

 private:
  const SimRunOptions& options_;
  SimSummary& summary_;
  std::unique_ptr<sim::Renderer> renderer_;
  std::unique_ptr<sim::Viewer> viewer_;
  double next_view_s_ = 0.0;
};

template <typename Command>
SimResult runWith(const SimRunOptions& options, const model::RobotDescription& robot) {
  constexpr bool kCartesian = std::is_same_v<Command, CartesianCommand>;
  SimResult result;
  SimSummary& summary = result.summary;
  SimLog& log = result.log;
  summary.robot = robot.name;
  summary.plugin = options.config.plugin;

  sim::PlantOptions plant_options;
  plant_options.substeps = options.task.substeps;
  plant_options.seed = options.task.seed;
  plant_options.scene = options.task.scene;
  plant_options.scene.offscreen_width = std::max(options.image_width, 1280);
  plant_options.scene.offscreen_height = std::max(options.image_height, 960);
  plant_options.tip_frame = options.config.tip_frame;
  plant_options.joint_dynamics = options.plant_joint_dynamics;
  plant_options.friction_scale = options.plant_friction_scale;
  sim::SimulatedRobot plant(robot, plant_options);

  pipeline::Wrapper<Command> wrapper(options.config);
  const int dof = wrapper.dof();
  if (dof != plant.dof()) {
    throw std::runtime_error("the controller has " + std::to_string(dof) +
                             " joints, the simulated " + robot.name + " " +
                             std::to_string(plant.dof()));
  }
  summary.dof = dof;
  summary.cartesian = kCartesian;
  log.dof = dof;
  log.cartesian = kCartesian;

  JointState state = JointState::zero(dof);
  plant.read(state);
  wrapper.activate(state);
  const Trajectory trajectory(options.task, startReference(wrapper.lastAccepted()));
  std::optional<task::PathCommand> path_stream;
  double end_of_motion = trajectory.endTime();
  if (options.task.path_points) {
    path_stream.emplace(task::Path(*options.task.path_points), options.task.path_options);
    end_of_motion = std::max(
        end_of_motion, options.task.path_options.start_time_s +
                           path_stream->path().length() / options.task.path_options.speed_m_per_s);
  }

  const double period_s = plant.controlPeriod();
  const double duration_s = options.duration_s > 0.0 ? options.duration_s : options.task.duration_s;
  const auto cycles = static_cast<std::size_t>(std::llround(duration_s / period_s));
  const auto send_every = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::llround(1.0 / (options.task.command_rate_hz * period_s))));
  const auto snapshot_every =
      options.task.snapshot_every_ms > 0.0
          ? std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(
                                         options.task.snapshot_every_ms * 1e-3 / period_s)))
          : std::size_t{0};

  Pictures pictures(options, plant, summary);
  pictures.snapshot(plant, "start");
  ProgressBar progress(options.progress, "sim " + robot.name, duration_s);

  std::vector<double> torque(static_cast<std::size_t>(dof), 0.0);
  std::vector<double> previous_torque(torque);
  std::size_t next_waypoint = 0;
  const Clock::time_point wall_start = Clock::now();
  bool window_open = true;
  for (std::size_t cycle = 0; cycle < cycles && window_open; ++cycle) {
    const double t = static_cast<double>(cycle) * period_s;
    plant.read(state);

    // Stream: waypoint fields the moment they come due, the motion reference at the command rate.
    bool send = cycle % send_every == 0;
    Command command = wrapper.lastAccepted();
    command.fields = CommandField::kPosition | CommandField::kVelocity;
    while (next_waypoint < options.task.waypoints.size() &&
           options.task.waypoints[next_waypoint].time_s <= t + 0.5 * period_s) {
      const Waypoint& waypoint = options.task.waypoints[next_waypoint];
      const Command& given = std::get<Command>(waypoint.command);  // typed at load
      schema::assign(command, given, waypoint.keys);
      command.fields = command.fields | given.fields;
      ++next_waypoint;
      send = true;
    }
    if constexpr (kCartesian) {
      if (path_stream && t >= options.task.path_options.start_time_s && send) {
        command = path_stream->commandAt(t, dof);
      } else if (options.cartesian_source && send) {
        command = options.cartesian_source(t);
      } else if (send) {
        setMotion(command, trajectory.at(t));
      }
    } else if (send) {
      setMotion(command, trajectory.at(t));
    }
    if (send) {
      command.stamp_s = t;
      const pipeline::Verdict verdict = wrapper.submit(command);
      ++summary.commands_sent;
      if (!verdict.accepted) {
        std::ostringstream message;
        message << "t = " << std::fixed << std::setprecision(3) << t
                << " s: command rejected: " << verdict.message;
        addMessage(summary, message.str(), options.progress);
      }
    }

    const pipeline::CycleStatus status = wrapper.update(state, period_s, torque);
    if (status != pipeline::CycleStatus::kInactive) {
      plant.write(torque);
    }

    const Command in_force = wrapper.lastAccepted();
    log.time_s.push_back(t);
    log.position.push_back(state.position);
    log.velocity.push_back(state.velocity);
    log.torque.push_back(Eigen::Map<const Eigen::VectorXd>(torque.data(), dof));
    const Eigen::Isometry3d tcp = plant.tcpPose();
    log.tcp_position.push_back(tcp.translation());
    log.tcp_orientation.push_back(Eigen::Quaterniond(tcp.linear()));
    log.contact_wrench.push_back(plant.toolContactWrench());
    if constexpr (kCartesian) {
      log.reference_position.push_back(in_force.position);
      log.reference_orientation.push_back(in_force.orientation);
    } else {
      log.joint_reference.push_back(in_force.position);
    }
    for (int j = 0; j < dof; ++j) {
      const double magnitude = std::abs(torque[j]);
      if (magnitude > summary.max_torque_nm) {
        summary.max_torque_nm = magnitude;
        summary.max_torque_joint = j;
      }
      if (cycle > 0) {
        summary.max_torque_rate_nm_per_s = std::max(
            summary.max_torque_rate_nm_per_s, std::abs(torque[j] - previous_torque[j]) / period_s);
      }
    }
    previous_torque = torque;

    plant.step();
    if (snapshot_every != 0 && (cycle + 1) % snapshot_every == 0 && cycle + 1 < cycles) {
      std::ostringstream name;
      name << "snapshot_" << std::setw(6) << std::setfill('0')
           << std::llround(plant.simTime() * 1000.0) << "ms";
      pictures.snapshot(plant, name.str());
    }
    window_open = pictures.show(plant, plant.simTime());
    if (options.realtime || options.view) {
      std::this_thread::sleep_until(wall_start +
                                    std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(plant.simTime())));
    }
    progress.update(plant.simTime(),
                    std::chrono::duration<double>(Clock::now() - wall_start).count());
  }
  progress.finish();
  summary.wall_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  summary.simulated_s = plant.simTime();
  pictures.snapshot(plant, "end");

  const pipeline::DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  summary.rejections = diagnostics.rejectionsTotal();
  summary.rate_limit_hits = diagnostics.rate_limit_hits;
  summary.effort_limit_hits = diagnostics.effort_limit_hits;
  summary.faults = diagnostics.faults;
  if (diagnostics.faults > 0) {
    addMessage(summary, "controller FAULT: " + diagnostics.last_error, options.progress);
  }

  if (!log.time_s.empty()) {
    const std::size_t last = log.size() - 1;
    if constexpr (kCartesian) {
      summary.final_position_error_mm = 1e3 * log.positionError(last);
      summary.final_orientation_error_deg = log.orientationError(last) * 180.0 / M_PI;
    } else {
      summary.final_joint_error_rad = log.jointError(last);
    }
    // Settling: the last row outside the band, counted from the last waypoint.
    std::optional<std::size_t> last_outside;
    for (std::size_t row = 0; row < log.size(); ++row) {
      const bool outside = kCartesian ? (log.positionError(row) > kSettlePositionM ||
                                         log.orientationError(row) > kSettleOrientationRad)
                                      : log.jointError(row) > kSettleJointRad;
      if (outside) {
        last_outside = row;
      }
    }
    if (!last_outside) {
      summary.settle_time_s = 0.0;
    } else if (*last_outside < last) {
      summary.settle_time_s = std::max(0.0, log.time_s[*last_outside + 1] - end_of_motion);
    }
  }
  return result;
}

}  // namespace

double SimLog::positionError(std::size_t row) const {
  return (reference_position.at(row) - tcp_position.at(row)).norm();
}

double SimLog::orientationError(std::size_t row) const {
  return reference_orientation.at(row).angularDistance(tcp_orientation.at(row));
}

double SimLog::jointError(std::size_t row) const {
  return (joint_reference.at(row) - position.at(row)).cwiseAbs().maxCoeff();
}

SimResult runSimulation(const SimRunOptions& options) {
  const model::RobotDescription robot = model::loadRobotDescription(options.config.robot);
  const int kind = plugin::PluginLibrary(options.config.plugin).api().command_kind;
  if (!options.out_dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(options.out_dir, error);
    if (error) {
      throw std::runtime_error("cannot create the output folder '" + options.out_dir.string() +
                               "': " + error.message());
    }
  }
  SimResult result = kind == COMPLY_COMMAND_CARTESIAN ? runWith<CartesianCommand>(options, robot)
                                                      : runWith<JointCommand>(options, robot);
  if (!options.out_dir.empty()) {
    const std::filesystem::path csv = options.out_dir / "log.csv";
    writeLogCsv(result.log, csv);
    result.summary.files.push_back(csv);
  }
  return result;
}

std::vector<Eigen::Vector3d> averagedContactForce(const SimLog& log, std::size_t window) {
  std::vector<Eigen::Vector3d> averaged(log.size(), Eigen::Vector3d::Zero());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < log.size(); ++i) {
    sum += log.contact_wrench[i].head<3>();
    if (i >= window) {
      sum -= log.contact_wrench[i - window].head<3>();
    }
    averaged[i] = sum / static_cast<double>(std::min(i + 1, window));
  }
  return averaged;
}

void writeLogCsv(const SimLog& log, const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) {
    throw std::runtime_error("cannot write '" + file.string() + "'");
  }
  out << "time_s";
  for (const char* prefix : {"q", "dq", "tau"}) {
    for (int j = 0; j < log.dof; ++j) {
      out << ',' << prefix << j;
    }
  }
  out << ",tcp_x,tcp_y,tcp_z,tcp_qx,tcp_qy,tcp_qz,tcp_qw";
  if (log.cartesian) {
    out << ",ref_x,ref_y,ref_z,ref_qx,ref_qy,ref_qz,ref_qw,position_error_mm,"
           "orientation_error_deg";
  } else {
    for (int j = 0; j < log.dof; ++j) {
      out << ",qref" << j;
    }
    out << ",joint_error_rad";
  }
  out << ",contact_fx,contact_fy,contact_fz,contact_tx,contact_ty,contact_tz\n";
  out << std::setprecision(9);
  const auto quaternion = [&](const Eigen::Quaterniond& q) {
    out << ',' << q.x() << ',' << q.y() << ',' << q.z() << ',' << q.w();
  };
  for (std::size_t row = 0; row < log.size(); ++row) {
    out << log.time_s[row];
    for (const auto* column : {&log.position, &log.velocity, &log.torque}) {
      for (int j = 0; j < log.dof; ++j) {
        out << ',' << (*column)[row][j];
      }
    }
    const Eigen::Vector3d& p = log.tcp_position[row];
    out << ',' << p.x() << ',' << p.y() << ',' << p.z();
    quaternion(log.tcp_orientation[row]);
    if (log.cartesian) {
      const Eigen::Vector3d& r = log.reference_position[row];
      out << ',' << r.x() << ',' << r.y() << ',' << r.z();
      quaternion(log.reference_orientation[row]);
      out << ',' << 1e3 * log.positionError(row) << ',' << log.orientationError(row) * 180.0 / M_PI;
    } else {
      for (int j = 0; j < log.dof; ++j) {
        out << ',' << log.joint_reference[row][j];
      }
      out << ',' << log.jointError(row);
    }
    for (int k = 0; k < 6; ++k) {
      out << ',' << log.contact_wrench[row][k];
    }
    out << '\n';
  }
  if (!out) {
    throw std::runtime_error("error while writing '" + file.string() + "'");
  }
}

void printSummary(const SimSummary& summary, std::ostream& out) {
  out << std::fixed;
  out << "robot " << summary.robot << " (" << summary.dof << " DOF), plugin " << summary.plugin
      << ": " << std::setprecision(2) << summary.simulated_s << " s simulated in " << summary.wall_s
      << " s (" << std::setprecision(1)
      << (summary.wall_s > 0 ? summary.simulated_s / summary.wall_s : 0.0) << "x real time)\n";
  if (summary.cartesian) {
    out << "  final pose error      " << std::setprecision(3) << summary.final_position_error_mm
        << " mm, " << summary.final_orientation_error_deg << " deg\n";
  } else {
    out << "  final joint error     " << std::setprecision(5) << summary.final_joint_error_rad
        << " rad\n";
  }
  out << "  settle time           ";
  if (std::isnan(summary.settle_time_s)) {
    out << "not settled\n";
  } else {
    out << std::setprecision(3) << summary.settle_time_s
        << " s after the last waypoint (band 1 mm, 0.5 deg)\n";
  }
  out << "  max torque            " << std::setprecision(2) << summary.max_torque_nm
      << " N m (joint " << summary.max_torque_joint << ")\n"
      << "  max torque rate       " << std::setprecision(1) << summary.max_torque_rate_nm_per_s
      << " N m/s\n"
      << "  rate-limit hits       " << summary.rate_limit_hits << " joint-cycles\n"
      << "  effort-limit hits     " << summary.effort_limit_hits << " joint-cycles\n"
      << "  commands              " << summary.commands_sent << " sent, " << summary.rejections
      << " rejected\n"
      << "  faults                " << summary.faults << "\n";
  for (const std::string& message : summary.messages) {
    out << "  note: " << message << "\n";
  }
  for (const std::filesystem::path& file : summary.files) {
    out << "  wrote " << file.string() << "\n";
  }
}

}  // namespace comply::app
