"""A comply robot in comply's MuJoCo plant under ros2_control, with a comply controller.

    ros2 launch comply_bringup comply.launch.py robot:=fr3 controller:=cartesian_impedance

robot:            comply robot name (or folder); its URDF plus its <ros2_control> block from
                  comply_mujoco_hardware is the robot_description
controller:       the controller's name, the top-level key of its file
controller_file:  comply's controller file (default: comply's config/sim/<controller>.yaml); its
                  `robot:` is replaced by the robot argument
kind:             cartesian | joint | auto (auto: joint when the plugin's name says so)
update_rate:      controller manager rate [Hz]
force_torque_sensor:  the wrist sensor's name for the controller (the MuJoCo hardware exports
                  tcp_fts_sensor/force.x ... /torque.z); empty (default): none is read
wrench_sensor_offset:  the simulated sensor's own offset, six numbers "fx fy fz tx ty tz" in its
                  axes [N, N m] (what a tare removes); empty (default): none

The plant is actuated as the controller file's output.mode says (torque unless it says
otherwise): its <ros2_control> block then lists that mode's command interfaces.

robot_state_publisher (and a joint_state_broadcaster for it) start when they are installed.
"""

import os
import tempfile

import yaml
from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def _comply_paths():
    with open(os.path.join(get_package_share_directory('comply_bringup'), 'comply_paths.yaml')) as f:
        return yaml.safe_load(f)


def _robot_folder(robot, paths):
    if os.sep in robot:
        return robot
    folders = [f for f in os.environ.get('COMPLY_ROBOT_PATH', '').split(':') if f]
    for folder in folders + [paths['robots']]:
        if os.path.isfile(os.path.join(folder, robot, 'robot.yaml')):
            return os.path.join(folder, robot)
    raise RuntimeError(f"no comply robot '{robot}' in COMPLY_ROBOT_PATH or {paths['robots']}")


# The command interfaces per joint of each output mode (comply_ros2_control/command_interfaces.hpp).
_MODE_INTERFACES = {
    'torque': ['effort'],
    'joint_pd': ['position', 'velocity', 'effort', 'stiffness', 'damping'],
    'position': ['position'],
    'velocity': ['velocity'],
}


def _actuated_block(block, mode, offset):
    """The torque block for a plant actuated by `mode`: its command interfaces and parameter; and
    the sensor's `offset` (six numbers as text, or empty)."""
    if mode not in _MODE_INTERFACES:
        raise RuntimeError(f"output.mode must be one of {', '.join(_MODE_INTERFACES)}, not '{mode}'")
    interfaces = ''.join(f'<command_interface name="{kind}"/>' for kind in _MODE_INTERFACES[mode])
    block = block.replace('<command_interface name="effort"/>', interfaces)
    parameters = f'  <param name="actuation">{mode}</param>\n'
    if offset:
        parameters += f'    <param name="wrench_sensor_offset">{offset}</param>\n'
    return block.replace('</hardware>', parameters + '  </hardware>', 1)


def _robot_description(folder, mode, offset):
    with open(os.path.join(folder, 'robot.yaml')) as f:
        urdf_file = yaml.safe_load(f)['urdf']
    with open(os.path.join(folder, urdf_file)) as f:
        urdf = f.read()
    name = os.path.basename(os.path.normpath(folder))
    block_file = os.path.join(get_package_share_directory('comply_mujoco_hardware'), 'urdf',
                              f'{name}.ros2_control.xml')
    if not os.path.isfile(block_file):
        raise RuntimeError(f'no ros2_control block for robot {name}: {block_file}')
    with open(block_file) as f:
        block = _actuated_block(f.read(), mode, offset)
    end = urdf.rfind('</robot>')
    return urdf[:end] + block + urdf[end:]


def _temporary_yaml(content, prefix):
    handle, path = tempfile.mkstemp(prefix=prefix, suffix='.yaml')
    with os.fdopen(handle, 'w') as f:
        yaml.safe_dump(content, f)
    return path


def _controller_file(controller, controller_file, robot, sensor):
    with open(controller_file) as f:
        content = yaml.safe_load(f)
    if not isinstance(content, dict) or controller not in content:
        raise RuntimeError(f"{controller_file} has no controller '{controller}' "
                           f"(its top-level keys: {', '.join(content or {})})")
    parameters = content[controller]['ros__parameters']
    parameters['robot'] = robot
    if sensor:
        parameters['force_torque_sensor.name'] = sensor
    return _temporary_yaml({controller: content[controller]}, f'comply_{controller}_'), parameters


def _installed(package):
    try:
        get_package_share_directory(package)
        return True
    except PackageNotFoundError:
        return False


def _launch(context):
    arg = lambda name: LaunchConfiguration(name).perform(context)  # noqa: E731
    paths = _comply_paths()
    robot, controller = arg('robot'), arg('controller')
    folder = _robot_folder(robot, paths)
    controller_file = arg('controller_file') or os.path.join(paths['config'], 'sim',
                                                             f'{controller}.yaml')
    controller_yaml, parameters = _controller_file(controller, controller_file, robot,
                                                   arg('force_torque_sensor'))
    mode = (parameters.get('output') or {}).get('mode') or parameters.get('output.mode') or 'torque'

    kind = arg('kind')
    if kind == 'auto':
        kind = 'joint' if 'joint' in str(parameters.get('plugin', '')) else 'cartesian'
    if kind not in ('cartesian', 'joint'):
        raise RuntimeError(f"kind must be cartesian, joint or auto, not '{kind}'")
    with_state_publisher = _installed('robot_state_publisher')
    managed = {controller: {'type': f'comply_ros2_control/{kind.capitalize()}Controller'}}
    if with_state_publisher:
        managed['joint_state_broadcaster'] = {
            'type': 'joint_state_broadcaster/JointStateBroadcaster'}
    manager_yaml = _temporary_yaml({'controller_manager': {'ros__parameters': {
        'update_rate': int(arg('update_rate')), **managed}}}, 'comply_controller_manager_')
    # A dictionary reaches every node of the process: the controller reads the same URDF.
    description = {'robot_description': _robot_description(folder, mode,
                                                          arg('wrench_sensor_offset'))}
    actions = [
        Node(package='controller_manager', executable='ros2_control_node', output='screen',
             parameters=[description, manager_yaml, controller_yaml]),
        Node(package='controller_manager', executable='spawner', output='screen',
             arguments=[controller, '--controller-manager', '/controller_manager',
                        '--controller-manager-timeout', '60']),
    ]
    if with_state_publisher:
        actions += [
            Node(package='robot_state_publisher', executable='robot_state_publisher',
                 parameters=[description]),
            Node(package='controller_manager', executable='spawner',
                 arguments=['joint_state_broadcaster', '--controller-manager',
                            '/controller_manager']),
        ]
    return actions


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('robot', default_value='fr3'),
        DeclareLaunchArgument('controller', default_value='cartesian_impedance'),
        DeclareLaunchArgument('controller_file', default_value=''),
        DeclareLaunchArgument('kind', default_value='auto'),
        DeclareLaunchArgument('update_rate', default_value='1000'),
        DeclareLaunchArgument('force_torque_sensor', default_value=''),
        DeclareLaunchArgument('wrench_sensor_offset', default_value=''),
        OpaqueFunction(function=_launch),
    ])
