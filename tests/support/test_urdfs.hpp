#pragma once
// Small URDFs whose kinematics and dynamics can be written down by hand.

#include <string>

namespace comply::test_urdfs {

/// A loop a -> b -> a under the root `base`: urdfdom accepts it, comply's model must not.
inline std::string kinematicLoop() {
  return R"(<robot name="loop"><link name="base"/><link name="a"/>
    <link name="b"/>
    <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" velocity="1" effort="10"/></joint>
    <joint name="j2" type="revolute"><parent link="b"/><child link="a"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" velocity="1" effort="10"/></joint></robot>)";
}

/// One revolute joint about y; a point-like 2 kg mass 0.5 m along x from the axis; tip at 1 m.
inline std::string pendulum() {
  return R"(<robot name="pendulum">
  <link name="base"/>
  <link name="arm">
    <inertial><origin xyz="0.5 0 0"/><mass value="2.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>
  </link>
  <link name="tip"/>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 1"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" velocity="2" effort="50"/></joint>
  <joint name="arm_to_tip" type="fixed"><parent link="arm"/><child link="tip"/>
    <origin xyz="1 0 0"/></joint>
</robot>)";
}

/// Planar arm in the x-z plane: two revolute joints about y, links of 1.0 m and 0.8 m, point
/// masses m1 = 3 kg and m2 = 2 kg at 0.4 m and 0.3 m along each link, rotational inertias I1, I2
/// about y, tip at the end of link 2. Link directions are +x at q = 0.
inline std::string planarTwoLink() {
  return R"(<robot name="planar">
  <link name="base"/>
  <link name="link1">
    <inertial><origin xyz="0.4 0 0"/><mass value="3.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.25" iyz="0" izz="0.25"/></inertial>
  </link>
  <link name="link2">
    <inertial><origin xyz="0.3 0 0"/><mass value="2.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.12" iyz="0" izz="0.12"/></inertial>
  </link>
  <link name="tip"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="link1"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" velocity="2" effort="50"/></joint>
  <joint name="elbow" type="continuous"><parent link="link1"/><child link="link2"/>
    <origin xyz="1.0 0 0"/><axis xyz="0 1 0"/><limit effort="30" velocity="3"/></joint>
  <joint name="tool" type="fixed"><parent link="link2"/><child link="tip"/>
    <origin xyz="0.8 0 0"/></joint>
</robot>)";
}

/// A vertical prismatic lift carrying a 4 kg mass, then a revolute joint about a skewed axis.
inline std::string liftAndSkewedHinge() {
  return R"(<robot name="lift">
  <link name="base"/>
  <link name="carriage">
    <inertial><origin xyz="0 0 0.1"/><mass value="4.0"/>
      <inertia ixx="0.05" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.02"/></inertial>
  </link>
  <link name="arm">
    <inertial><origin xyz="0.2 0.1 0" rpy="0.3 0.2 0.1"/><mass value="1.5"/>
      <inertia ixx="0.02" ixy="0.001" ixz="0" iyy="0.03" iyz="0.002" izz="0.04"/></inertial>
  </link>
  <link name="tip"/>
  <joint name="lift" type="prismatic"><parent link="base"/><child link="carriage"/>
    <origin xyz="0.1 0 0.2"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.5" velocity="0.3" effort="200"/></joint>
  <joint name="skew" type="revolute"><parent link="carriage"/><child link="arm"/>
    <origin xyz="0 0 0.3" rpy="0.1 -0.2 0.3"/><axis xyz="1 1 1"/>
    <limit lower="-2" upper="2" velocity="2" effort="40"/></joint>
  <joint name="tool" type="fixed"><parent link="arm"/><child link="tip"/>
    <origin xyz="0.4 0 0.05" rpy="0 0.5 0"/></joint>
</robot>)";
}

/// Chain of n revolute joints (for the DOF limit): joint names j0..j{n-1}, tip link "l{n}".
inline std::string longChain(int joints) {
  std::string urdf = "<robot name=\"long\"><link name=\"l0\"/>";
  for (int i = 0; i < joints; ++i) {
    const std::string parent = "l" + std::to_string(i);
    const std::string child = "l" + std::to_string(i + 1);
    urdf += "<link name=\"" + child +
            "\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" "
            "iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link>";
    urdf += "<joint name=\"j" + std::to_string(i) + "\" type=\"revolute\"><parent link=\"" +
            parent + "\"/><child link=\"" + child +
            "\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"0 0 1\"/>"
            "<limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/></joint>";
  }
  return urdf + "</robot>";
}

/// Base, a floating and a planar joint somewhere, for rejection tests.
inline std::string withJointType(const std::string& type) {
  return R"(<robot name="odd">
  <link name="base"/><link name="mid"/><link name="tip"/>
  <joint name="odd_joint" type=")" +
         type + R"("><parent link="base"/><child link="mid"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
  <joint name="hinge" type="revolute"><parent link="mid"/><child link="tip"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
</robot>)";
}

}  // namespace comply::test_urdfs
