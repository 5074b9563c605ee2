function [x, fval, exitflag] = fmincon(fun, x0, A, b, Aeq, beq, lb, ub, nonlcon, options)
% Octave stand-in for MATLAB's fmincon, covering only the bound-constrained call used by
% mobius_area_correction_spherical (no linear/nonlinear constraints): Octave's core sqp
% (BFGS SQP, finite-difference gradients) with the same bounds.
if ~(isempty(A) && isempty(Aeq) && isempty(nonlcon)), error('fmincon shim: bounds only'); end
sz = size(x0);
[xc, fval, info] = sqp(x0(:), @(y) fun(reshape(y, sz)), [], [], lb(:), ub(:), 400, 1e-8);
x = reshape(xc, sz); exitflag = double(info == 101 || info == 104);
end
