function o = optimoptions(solver, varargin)
% Octave stand-in for MATLAB's optimoptions (Optimization Toolbox): returns a plain struct.
o = struct('solver', solver);
for k = 1:2:numel(varargin), o.(varargin{k}) = varargin{k+1}; end
end
