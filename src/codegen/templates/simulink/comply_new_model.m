function comply_new_model(name, kind)
%COMPLY_NEW_MODEL Template model for a comply control law (written by comply codegen simulink).
%   comply_new_model('my_law', 'joint') or comply_new_model('my_law', 'cartesian') creates and
%   saves my_law.slx: bus inports `input` (comply_input) and `command` (comply_joint_command or
%   comply_cartesian_command) and the outport `torque` (COMPLY_MAX_DOF doubles), wired to the
%   empty subsystem `control_law` where the law is drawn. Fixed step 1 ms, ERT target, reusable
%   function code interface with root-level I/O as structures: the configuration
%   comply_simulink_adapter.c is written for. Build with Ctrl+B (or slbuild), then point the
%   CMakeLists.txt next to this file at the generated NAME_ert_rtw folder.
if nargin < 2
  kind = 'joint';
end
switch kind
  case 'joint'
    command_bus = 'comply_joint_command';
  case 'cartesian'
    command_bus = 'comply_cartesian_command';
  otherwise
    error('comply:kind', 'kind must be joint or cartesian, not %s', kind);
end
comply_buses();
max_dof = COMPLY_MAX_DOF_VALUE;

new_system(name);
add_block('simulink/Sources/In1', [name '/input'], 'OutDataTypeStr', 'Bus: comply_input', ...
          'Position', [40 40 70 54]);
add_block('simulink/Sources/In1', [name '/command'], 'OutDataTypeStr', ['Bus: ' command_bus], ...
          'Position', [40 100 70 114]);
add_block('simulink/Sinks/Out1', [name '/torque'], 'OutDataTypeStr', 'double', ...
          'PortDimensions', num2str(max_dof), 'Position', [400 70 430 84]);

law = [name '/control_law'];
add_block('simulink/Ports & Subsystems/Subsystem', law, 'Position', [180 30 300 130]);
% The library subsystem holds In1 -> Out1; the template wants two inputs and a zero torque that
% the user replaces with the law.
delete_line(law, 'In1/1', 'Out1/1');
set_param([law '/In1'], 'Name', 'input');
add_block('simulink/Sources/In1', [law '/command']);
set_param([law '/Out1'], 'Name', 'torque');
add_block('simulink/Sources/Constant', [law '/zero_torque'], ...
          'Value', sprintf('zeros(%d, 1)', max_dof), 'OutDataTypeStr', 'double');
add_line(law, 'zero_torque/1', 'torque/1');

add_line(name, 'input/1', 'control_law/1');
add_line(name, 'command/1', 'control_law/2');
add_line(name, 'control_law/1', 'torque/1');

set_param(name, 'SolverType', 'Fixed-step', 'Solver', 'FixedStepDiscrete', ...
          'FixedStep', '0.001', 'StopTime', 'inf');
set_param(name, 'SystemTargetFile', 'ert.tlc', 'TargetLang', 'C', ...
          'CodeInterfacePackaging', 'Reusable function', 'RootIOFormat', 'Structure reference', ...
          'DefaultParameterBehavior', 'Tunable', 'CombineOutputUpdateFcns', 'on', ...
          'IncludeMdlTerminateFcn', 'on', 'GenerateSampleERTMain', 'off', ...
          'GenCodeOnly', 'on', 'ProdHWDeviceType', 'Intel->x86-64 (Linux 64)');
save_system(name);
end
