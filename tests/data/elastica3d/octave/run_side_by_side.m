% usage: octave run_side_by_side.m <case>; times Elastica3D on the five N = 100 cases of docs/performance.md
% ("Side by side with the published model") and writes side_<case>.json.
warning('off','all');
args = argv(); k = str2double(args{1});
% {whisker, mode, force-mode fsz that makes the load / the contact}
list = {'planar100','force',[1e-3 0.015 0]; 'planar100','point',[1e-3 0.015 0];
        'spatial100','point',[1e-3 0.016 0.2]; 'planar100','peg',[1e-3 0.015 0];
        'spatial100','peg',[2e-3 0.009 -1.3]};
[X, I] = whiskers(list{k,1}); fsz = list{k,3};
tic;
[x3,y3,z3,F,PP] = elastica3D(X(1,:),X(2,:),X(3,:),{fsz},'mode','force','I',I,'BC','e');
t_force = toc;
pos = F.pos; [~, nn] = min(abs(PP.s - fsz(2)));
tangent = pos - [x3(nn-1); y3(nn-1); z3(nn-1)];
d = cross(F.f, tangent); d = d/norm(d);
G = F; t = t_force;
if strcmp(list{k,2}, 'point')
  tic; [~,~,~,G] = elastica3D(X(1,:),X(2,:),X(3,:),{pos},'mode','point','I',I,'BC','e'); t = toc;
elseif strcmp(list{k,2}, 'peg')
  tic; [~,~,~,G] = elastica3D(X(1,:),X(2,:),X(3,:),{pos, d},'mode','peg','I',I,'BC','e'); t = toc;
end
if ~isfield(G, 'fsz'), G.fsz = fsz; end
fid = fopen(sprintf('side_%d.json', k),'w');
fprintf(fid, '{"case": %d, "whisker": "%s", "mode": "%s", "made_by": {"force": %.17g, "arc_length": %.17g, "zeta": %.17g},\n', k, list{k,1}, list{k,2}, fsz);
fprintf(fid, ' "point_W": [%.17g, %.17g, %.17g], "direction_W": [%.17g, %.17g, %.17g],\n', pos, d);
fprintf(fid, ' "elastica3d": {"force": %.17g, "arc_length": %.17g, "zeta": %.17g, "force_W": [%.17g, %.17g, %.17g], "moment_W": [%.17g, %.17g, %.17g], "contact_W": [%.17g, %.17g, %.17g], "seconds": %.4g}}\n', G.fsz, G.f, G.m, G.pos, t);
fclose(fid);
