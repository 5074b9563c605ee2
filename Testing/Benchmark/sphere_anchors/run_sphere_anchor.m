function run_sphere_anchor(method, mesh, out_off, anchor_dir, nrep)
% Run one published spherical-map anchor on a closed genus-0 mesh and write the map as OFF.
%  method: 'flash' -> spherical_conformal_map(v,f)            (garyptchoi/spherical-conformal-map)
%          'flash_mobius' -> FLASH, then the repo's extension mobius_area_correction_spherical
%          'sdem'  -> FLASH + Mobius area correction, then SDEM with population = face areas
%                     of the surface (area-preserving use, demo_SDEM.m Example 3), defaults
%                     dt=0.1, epsilon=1e-3, max_iter=200 (garyptchoi/spherical-density-equalizing-map)
%  nrep: timing repetitions (median reported; only 1 if the first run takes > 60 s).
if nargin < 5, nrep = 1; end
here = fileparts(mfilename('fullpath'));
if exist('fmincon') ~= 2 && exist('fmincon') ~= 5, addpath(fullfile(here, 'octave_shims')); end
switch method
  case 'flash', addpath(fullfile(anchor_dir, 'mfile'));
  case 'flash_mobius', addpath(fullfile(anchor_dir, 'mfile'), fullfile(anchor_dir, 'extension'));
  case 'sdem',  addpath(fullfile(anchor_dir, 'code'));
  otherwise, error('unknown method %s', method);
end
[v, f] = read_tri_mesh(mesh);
t = zeros(nrep, 1); c = zeros(nrep, 1); t_parts = zeros(nrep, 3);
for k = 1:nrep
  t0 = tic; c0 = cputime;
  switch method
    case 'flash'
      X = spherical_conformal_map(v, f);
    case 'flash_mobius'
      X = mobius_area_correction_spherical(v, f, spherical_conformal_map(v, f));
    case 'sdem'
      S1 = spherical_conformal_map(v, f);            t1 = toc(t0);
      [S, mob] = mobius_area_correction_spherical(v, f, S1); t2 = toc(t0);
      sdem_log = evalc('X = SDEM(v, f, face_area(f, v), S, 0.1, 1e-3, 200);'); % per-step printout
      t_parts(k, :) = [t1, t2 - t1, toc(t0) - t2];
  end
  t(k) = toc(t0); c(k) = cputime - c0;   % CPU seconds too: robust when the machine is loaded
  if t(1) > 60, t = t(1); c = c(1); t_parts = t_parts(1, :); break; end   % slow: one run is enough
end
X = X ./ sqrt(sum(X.^2, 2));                         % normalize to the unit sphere
% Orientation: the mesh is outward-oriented; a map that mirrors the sphere would turn every
% triangle clockwise.  Detect by the sign of the total det(a,b,c) and undo with a reflection.
vol = sum(dot(X(f(:,1),:), cross(X(f(:,2),:), X(f(:,3),:), 2), 2));
reflected = vol < 0;
if reflected, X(:, 1) = -X(:, 1); end
write_sphere_off(out_off, X, f);
fprintf('RESULT method=%s nv=%d nf=%d seconds_median=%.3f seconds_all=%s cpu_median=%.3f reflected=%d\n', ...
        method, size(v,1), size(f,1), median(t), mat2str(t', 4), median(c), reflected);
if strcmp(method, 'sdem')
  L = strsplit(strtrim(sdem_log), "\n");          % last line: "<step>  <std(rho)/mean(rho)>"
  fprintf('RESULT sdem parts (flash, mobius, sdem) median: %s  last_step: %s  mobius_x=%s\n', ...
          mat2str(median(t_parts, 1), 4), strtrim(L{end}), mat2str(mob, 6));
end
end

