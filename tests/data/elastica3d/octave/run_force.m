% Elastica3D force mode on the fixture whiskers; prints one JSON object per case.
warning('off','all');
cases = {
 'planar30', 'e', [1e-3 0.015 0], 'planar30', 'e', [1e-3 0.015 pi/2], 'planar30', 'e', [2e-3 0.021 2.5],
 'planar30', 'e', [0.5e-3 0.0225 pi], 'planar30', 'e', [5e-3 0.0075 -1.0], 'planar30', 'e', [3e-3 0.0017 0.3],
 'planar30', 'e', [20e-3 0.012 0.8], 'planar30', 'e', [0.2e-3 0.0299 -2.0], 'planar30', 'r', [1e-3 0.0185 1.1],
 'spatial40', 'e', [1e-3 0.016 0.2], 'spatial40', 'e', [2e-3 0.009 -1.3], 'spatial40', 'e', [0.4e-3 0.027 2.9],
 'spatial40', 'e', [4e-3 0.0012 0.6], 'spatial40', 'e', [10e-3 0.013 -2.4], 'spatial40', 'r', [1.5e-3 0.02 1.7]};
fid = fopen('force_cases.json','w');
fprintf(fid, '[\n');
list = reshape(cases', 3, [])';
for k = 1:size(list,1)
  [X, I] = whiskers(list{k,1});
  fsz = list{k,3};
  [x3,y3,z3,F] = elastica3D(X(1,:),X(2,:),X(3,:),{fsz},'mode','force','I',I,'BC',list{k,2});
  fprintf(fid, '{"whisker": "%s", "base": "%s", "force": %.17g, "arc_length": %.17g, "zeta": %.17g,\n', list{k,1}, ...
          ifelse_str(list{k,2}), fsz(1), fsz(2), fsz(3));
  fprintf(fid, ' "force_W": [%.17g, %.17g, %.17g], "moment_W": [%.17g, %.17g, %.17g], "contact_W": [%.17g, %.17g, %.17g]}', F.f, F.m, F.pos);
  if k < size(list,1), fprintf(fid, ',\n'); else fprintf(fid, '\n'); end
end
fprintf(fid, ']\n'); fclose(fid);
