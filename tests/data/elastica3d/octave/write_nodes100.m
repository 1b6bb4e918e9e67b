% whiskers100.json: the rest nodes of the N = 100 side-by-side whiskers.
warning('off','all');
fid = fopen('whiskers100.json','w'); fprintf(fid,'{\n');
names = {'planar100','spatial100'};
for k = 1:2
  [X, I] = whiskers(names{k});
  fprintf(fid,' "%s": [', names{k});
  for i = 1:size(X,2)
    fprintf(fid,'[%.17g, %.17g, %.17g]', X(:,i)); if i < size(X,2), fprintf(fid, ', '); end
  end
  if k < 2, fprintf(fid,'],\n'); else fprintf(fid,']\n'); end
end
fprintf(fid,'}\n'); fclose(fid);
