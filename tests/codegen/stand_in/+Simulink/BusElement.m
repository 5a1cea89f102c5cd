function element = BusElement()
%BUSELEMENT Minimal stand-in for Simulink.BusElement with Simulink's defaults.
element = struct('Name', 'a', 'Dimensions', 1, 'DataType', 'double', 'Complexity', 'real', ...
                 'Description', '');
end
