% usage: octave run_contact.m <case>; Elastica3D point/peg mode through a contact that its force mode made.
warning('off','all');
args = argv(); k = str2double(args{1});
% {whisker, BC, force-mode fsz that makes the contact, mode}
list = {'planar30','e',[1e-3 0.015 0],'point'; 'planar30','e',[0.5e-3 0.0225 pi],'point';
        'spatial40','e',[1e-3 0.016 0.2],'point'; 'planar30','e',[1e-3 0.015 0],'peg';
        'spatial40','e',[2e-3 0.009 -1.3],'peg'; 'planar30','e',[2e-3 0.021 2.5],'point'};
[X, I] = whiskers(list{k,1}); fsz = list{k,3};
[x3,y3,z3,F,PP] = elastica3D(X(1,:),X(2,:),X(3,:),{fsz},'mode','force','I',I,'BC',list{k,2});
pos = F.pos; [~, nn] = min(abs(PP.s - fsz(2)));
tangent = pos - [x3(nn-1); y3(nn-1); z3(nn-1)];
d = cross(F.f, tangent); d = d/norm(d);
tic;
if strcmp(list{k,4}, 'point')
  [~,~,~,G] = elastica3D(X(1,:),X(2,:),X(3,:),{pos},'mode','point','I',I,'BC',list{k,2});
  C = pos; 
else
  [~,~,~,G] = elastica3D(X(1,:),X(2,:),X(3,:),{pos, d},'mode','peg','I',I,'BC',list{k,2});
end
t = toc;
% residual as Elastica3D defines it (its cost function) at the returned load
fid = fopen(sprintf('contact_%d.json', k),'w');
fprintf(fid, '{"whisker": "%s", "mode": "%s", "made_by": {"force": %.17g, "arc_length": %.17g, "zeta": %.17g},\n', list{k,1}, list{k,4}, fsz);
fprintf(fid, ' "point_W": [%.17g, %.17g, %.17g], "direction_W": [%.17g, %.17g, %.17g],\n', pos, d);
fprintf(fid, ' "elastica3d": {"force": %.17g, "arc_length": %.17g, "zeta": %.17g, "force_W": [%.17g, %.17g, %.17g], "moment_W": [%.17g, %.17g, %.17g], "contact_W": [%.17g, %.17g, %.17g], "seconds": %.3g}}\n', G.fsz, G.f, G.m, G.pos, t);
fclose(fid);
