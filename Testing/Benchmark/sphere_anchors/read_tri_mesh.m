function [v, f] = read_tri_mesh(path)
% Read a triangle mesh from .off or .obj (our own minimal reader; 1-based f).
txt = fileread(path);
[~, ~, ext] = fileparts(lower(path));
if strcmp(ext, '.off')
  txt = regexprep(txt, '#[^\n]*', '');            % strip comments
  txt = regexprep(txt, '^\s*[A-Za-z]*OFF', '');    % strip header keyword
  a = sscanf(txt, '%f');
  nv = a(1); nf = a(2); p = 4;
  v = reshape(a(p:p+3*nv-1), 3, nv)'; p = p + 3*nv;
  rows = reshape(a(p:p+4*nf-1), 4, nf)';
  if any(rows(:,1) ~= 3), error('read_tri_mesh: non-triangle face in %s', path); end
  f = rows(:, 2:4) + 1;
elseif strcmp(ext, '.obj')
  lines = strsplit(txt, "\n");
  isv = strncmp(lines, 'v ', 2); isf = strncmp(lines, 'f ', 2);
  v = sscanf(strjoin(cellfun(@(s) s(3:end), lines(isv), 'UniformOutput', false), ' '), '%f');
  v = reshape(v, 3, [])';
  fl = regexprep(lines(isf), '/[^\s]*', '');      % drop /vt/vn parts
  f = sscanf(strjoin(cellfun(@(s) s(3:end), fl, 'UniformOutput', false), ' '), '%d');
  f = reshape(f, 3, [])';
  f(f < 0) = size(v, 1) + 1 + f(f < 0);           % negative (relative) indices
else
  error('read_tri_mesh: unsupported extension %s', ext);
end
end
