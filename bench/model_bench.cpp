// Per-robot timing of one model update for each quantity set a controller asks for, beside Orocos
// KDL's solvers computing the same quantities. Run through `make bench`, which pins the process to
// one core. Each benchmark cycles through a fixed set of random configurations so the branch
// predictor and caches see a realistic sequence, not one repeated input.

#include <benchmark/benchmark.h>

#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/jacobian.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntspaceinertiamatrix.hpp>
#include <random>
#include <string>
#include <vector>

#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "kdl_chain.hpp"

namespace {

using comply::model::Quantity;

constexpr int kSampleCount = 256;
constexpr double kGravity = 9.81;

struct Samples {
  std::vector<std::vector<double>> q;
  std::vector<std::vector<double>> dq;
};

Samples drawSamples(const comply::model::Model& model) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Samples samples;
  for (int s = 0; s < kSampleCount; ++s) {
    std::vector<double> q(model.dof());
    std::vector<double> dq(model.dof());
    for (int i = 0; i < model.dof(); ++i) {
      q[i] = 2.5 * unit(rng);
      dq[i] = 1.5 * unit(rng);
    }
    samples.q.push_back(std::move(q));
    samples.dq.push_back(std::move(dq));
  }
  return samples;
}

void benchComply(benchmark::State& state, const std::string& robot, Quantity quantities) {
  const comply::model::RobotDescription description = comply::model::loadRobotDescription(robot);
  const comply::model::Model model = description.loadModel();
  comply::model::Data data(model);
  const Samples samples = drawSamples(model);
  int index = 0;
  for (auto _ : state) {
    const auto status =
        comply::model::update(model, data, samples.q[index], samples.dq[index], quantities);
    benchmark::DoNotOptimize(status);
    benchmark::DoNotOptimize(data.tip_position.data());
    benchmark::ClobberMemory();
    index = (index + 1) % kSampleCount;
  }
}

/// The KDL solvers a controller would hold; built once, reused every call like ours.
struct KdlSolvers {
  comply::testing::KdlUrdfChain urdf_chain;
  KDL::ChainFkSolverPos_recursive fk;
  KDL::ChainJntToJacSolver jacobian;
  KDL::ChainDynParam dynamics;
  KDL::JntArray q, dq, gravity, coriolis;
  KDL::Jacobian jac;
  KDL::JntSpaceInertiaMatrix mass;
  KDL::Frame pose;

  explicit KdlSolvers(comply::testing::KdlUrdfChain chain)
      : urdf_chain(std::move(chain)),
        fk(urdf_chain.chain),
        jacobian(urdf_chain.chain),
        dynamics(urdf_chain.chain, KDL::Vector(0.0, 0.0, -kGravity)) {
    const unsigned n = urdf_chain.chain.getNrOfJoints();
    q.resize(n);
    dq.resize(n);
    gravity.resize(n);
    coriolis.resize(n);
    jac.resize(n);
    mass.resize(n);
  }
};

void benchKdl(benchmark::State& state, const std::string& robot, Quantity quantities) {
  const comply::model::RobotDescription description = comply::model::loadRobotDescription(robot);
  const comply::model::Model model = description.loadModel();
  KdlSolvers kdl(comply::testing::kdlChainFromUrdf(description.urdf_path.string(),
                                                   description.base_frame, description.tcp_frame));
  const Samples samples = drawSamples(model);
  const auto wants = [quantities](Quantity q) { return (quantities & q) != Quantity::kNone; };
  int index = 0;
  for (auto _ : state) {
    // Samples are in URDF chain order for both, which is how the robot descriptions list joints.
    for (int i = 0; i < model.dof(); ++i) {
      kdl.q(i) = samples.q[index][i];
      kdl.dq(i) = samples.dq[index][i];
    }
    if (wants(Quantity::kPose)) {
      kdl.fk.JntToCart(kdl.q, kdl.pose);
    }
    if (wants(Quantity::kJacobian)) {
      kdl.jacobian.JntToJac(kdl.q, kdl.jac);
    }
    if (wants(Quantity::kGravity)) {
      kdl.dynamics.JntToGravity(kdl.q, kdl.gravity);
    }
    if (wants(Quantity::kCoriolis)) {
      kdl.dynamics.JntToCoriolis(kdl.q, kdl.dq, kdl.coriolis);
    }
    if (wants(Quantity::kMassMatrix)) {
      kdl.dynamics.JntToMass(kdl.q, kdl.mass);
    }
    benchmark::DoNotOptimize(kdl.pose.p.data);
    benchmark::ClobberMemory();
    index = (index + 1) % kSampleCount;
  }
}

struct QuantitySet {
  const char* name;
  Quantity quantities;
};

const QuantitySet kQuantitySets[] = {
    {"pose+jacobian", Quantity::kPose | Quantity::kJacobian},
    {"gravity", Quantity::kGravity},
    {"coriolis", Quantity::kCoriolis},
    {"mass_matrix", Quantity::kMassMatrix},
    {"pose+jacobian+gravity", Quantity::kPose | Quantity::kJacobian | Quantity::kGravity},
    {"all_but_payload", Quantity::kPose | Quantity::kJacobian | Quantity::kGravity |
                            Quantity::kCoriolis | Quantity::kMassMatrix},
};

const int kRegistered = [] {
  for (const std::string& robot : comply::model::availableRobots()) {
    for (const QuantitySet& set : kQuantitySets) {
      const std::string robot_name = robot;
      const Quantity quantities = set.quantities;
      benchmark::RegisterBenchmark(
          (robot_name + "/comply/" + set.name).c_str(),
          [robot_name, quantities](benchmark::State& s) { benchComply(s, robot_name, quantities); })
          ->Unit(benchmark::kNanosecond);
      benchmark::RegisterBenchmark(
          (robot_name + "/kdl/" + set.name).c_str(),
          [robot_name, quantities](benchmark::State& s) { benchKdl(s, robot_name, quantities); })
          ->Unit(benchmark::kNanosecond);
    }
  }
  return 0;
}();

}  // namespace

BENCHMARK_MAIN();
