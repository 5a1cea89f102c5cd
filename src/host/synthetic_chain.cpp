#include "comply/host/synthetic_chain.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "comply/core/capacity.hpp"

namespace comply::host {

std::string syntheticChainName(int dof) {
  return "chain" + std::to_string(dof);
}

int syntheticChainDof(const std::string& name) {
  if (name.rfind("chain", 0) != 0 || name.size() <= 5 || name.size() > 7) {
    return 0;
  }
  for (std::size_t i = 5; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') {
      return 0;
    }
  }
  const int dof = std::stoi(name.substr(5));
  return dof >= 1 && dof <= kMaxDof ? dof : 0;
}

namespace {

std::string urdf(int dof) {
  std::ostringstream out;
  out << "<robot name=\"" << syntheticChainName(dof) << "\">\n  <link name=\"base\"/>\n";
  for (int i = 0; i < dof; ++i) {
    // A solid cylinder of radius r and length l along z, centred half-way: physical inertias.
    const double length = 0.30 - 0.015 * i;
    const double mass = 4.0 - 0.25 * i;
    const double radius = 0.05;
    const double axial = 0.5 * mass * radius * radius;
    const double transverse = mass * (3.0 * radius * radius + length * length) / 12.0;
    out << "  <link name=\"link" << i + 1 << "\">\n    <inertial><origin xyz=\"0 0 " << 0.5 * length
        << "\"/><mass value=\"" << mass << "\"/>\n      <inertia ixx=\"" << transverse
        << "\" ixy=\"0\" ixz=\"0\" iyy=\"" << transverse << "\" iyz=\"0\" izz=\"" << axial
        << "\"/></inertial>\n  </link>\n";
    const double previous_length = i == 0 ? 0.1 : 0.30 - 0.015 * (i - 1);
    out << "  <joint name=\"joint" << i + 1 << "\" type=\"revolute\"><parent link=\""
        << (i == 0 ? std::string("base") : "link" + std::to_string(i)) << "\"/><child link=\"link"
        << i + 1 << "\"/>\n    <origin xyz=\"0 0 " << previous_length << "\"/><axis xyz=\""
        << (i % 2 == 0 ? "0 0 1" : "0 1 0")
        << "\"/><limit lower=\"-2.9\" upper=\"2.9\" velocity=\"2\" effort=\"100\"/></joint>\n";
  }
  const double last_length = 0.30 - 0.015 * (dof - 1);
  out << "  <link name=\"flange\"/>\n  <joint name=\"to_flange\" type=\"fixed\"><parent link=\"link"
      << dof << "\"/><child link=\"flange\"/><origin xyz=\"0 0 " << last_length
      << "\"/></joint>\n  <link name=\"tcp\"/>\n  <joint name=\"to_tcp\" type=\"fixed\"><parent "
         "link=\"flange\"/><child link=\"tcp\"/><origin xyz=\"0 0 0.1\"/></joint>\n</robot>\n";
  return out.str();
}

std::string robotYaml(int dof) {
  std::ostringstream out;
  out << "name: " << syntheticChainName(dof) << "\ndescription: synthetic " << dof
      << "-DOF chain for comply bench\nurdf: " << syntheticChainName(dof) << ".urdf\njoints: [";
  for (int i = 0; i < dof; ++i) {
    out << (i > 0 ? ", " : "") << "joint" << i + 1;
  }
  // Bent at every y joint, so the chain is far from straight (singular) at home.
  out << "]\nbase_frame: base\nflange_frame: flange\ntcp_frame: tcp\nhome: [";
  for (int i = 0; i < dof; ++i) {
    out << (i > 0 ? ", " : "") << (i % 2 == 0 ? 0.2 : 0.5 - 0.05 * i);
  }
  // Rotors as a real arm has them (0.1 kg m^2 reflected, as an arm of this size): without them
  // its light links could not render the default gains at 1 kHz (pipeline/gain_bound.hpp).
  out << "]\njoint_dynamics:\n  damping: [";
  for (int i = 0; i < dof; ++i) {
    out << (i > 0 ? ", " : "") << 0.0;
  }
  out << "]\n  armature: [";
  for (int i = 0; i < dof; ++i) {
    out << (i > 0 ? ", " : "") << 0.1;
  }
  out << "]\n  frictionloss: [";
  for (int i = 0; i < dof; ++i) {
    out << (i > 0 ? ", " : "") << 0.0;
  }
  out << "]\n";
  return out.str();
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream file(path);
  file << text;
  if (!file) {
    throw std::runtime_error("cannot write " + path.string());
  }
}

}  // namespace

std::filesystem::path writeSyntheticChain(int dof, const std::filesystem::path& folder) {
  if (dof < 1 || dof > kMaxDof) {
    throw std::invalid_argument("synthetic chain: 1 to " + std::to_string(kMaxDof) + " joints");
  }
  std::filesystem::create_directories(folder);
  writeFile(folder / (syntheticChainName(dof) + ".urdf"), urdf(dof));
  writeFile(folder / "robot.yaml", robotYaml(dof));
  return folder;
}

}  // namespace comply::host
