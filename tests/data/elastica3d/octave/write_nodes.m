% whiskers.json: the rest nodes given to Elastica3D. A caller may set `names` and `out` first
% (write_nodes100.m: the side-by-side whiskers).
warning('off','all');
if ~exist('names', 'var'), names = {'planar30','spatial40'}; out = 'whiskers.json'; end
fid = fopen(out,'w'); fprintf(fid,'{\n');
for k = 1:numel(names)
  [X, I] = whiskers(names{k});
  fprintf(fid,' "%s": [', names{k});
  for i = 1:size(X,2)
    fprintf(fid,'[%.17g, %.17g, %.17g]', X(:,i)); if i < size(X,2), fprintf(fid, ', '); end
  end
  if k < numel(names), fprintf(fid,'],\n'); else fprintf(fid,']\n'); end
end
fprintf(fid,'}\n'); fclose(fid);
