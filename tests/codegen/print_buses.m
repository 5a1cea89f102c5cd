% Runs the generated comply_buses.m against the stand-in and prints every bus the way
% abi_layout_dump prints abi.h: one line per element, then the C size of a struct laid out from the
% bus alone (natural alignment), so a wrong type, count or order shows up as a different size.
comply_buses();
sizes = struct('double', 8, 'int32', 4, 'uint32', 4, 'int8', 1);
for name = {'comply_input', 'comply_joint_command', 'comply_cartesian_command', 'comply_output'}
  bus = evalin('base', name{1});
  if ~strcmp(bus.DataScope, 'Imported') || ~strcmp(bus.HeaderFile, 'comply/plugin/abi.h')
    error('bus %s is not imported from comply/plugin/abi.h', name{1});
  end
  offset = 0;
  alignment = 1;
  for k = 1:numel(bus.Elements)
    e = bus.Elements(k);
    scalar = sizes.(e.DataType);
    offset = ceil(offset / scalar) * scalar;
    printf('%s %s %d %s %d\n', name{1}, e.Name, e.Dimensions, e.DataType, offset);
    offset = offset + scalar * e.Dimensions;
    alignment = max(alignment, scalar);
  end
  printf('%s sizeof %d\n', name{1}, ceil(offset / alignment) * alignment);
end
