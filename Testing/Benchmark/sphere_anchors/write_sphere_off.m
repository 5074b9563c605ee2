function write_sphere_off(path, X, f)
% Write OFF: vertex positions X (points on the unit sphere), the input's triangles (1-based f).
fid = fopen(path, 'w');
fprintf(fid, 'OFF\n%d %d 0\n', size(X, 1), size(f, 1));
fprintf(fid, '%.17g %.17g %.17g\n', X');          % full double precision
fprintf(fid, '3 %d %d %d\n', (f - 1)');
fclose(fid);
end
