function bus = Bus()
%BUS Minimal stand-in for Simulink.Bus: the properties comply_buses.m sets, as a struct, so the
%   generated script runs in Octave without Simulink.
bus = struct('Description', '', 'DataScope', 'Auto', 'HeaderFile', '', 'Elements', []);
end
