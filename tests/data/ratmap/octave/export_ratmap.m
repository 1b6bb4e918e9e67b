% Our driver for the RatMap Toolbox v1.1 (Towal et al. 2011): runs Get_RatMap with its default parameters for
% each of its three TGL_PHI methods and writes the numbers vibrissa is tested against. Run it in a directory
% that holds the toolbox's Get_RatMap.m (see ../README.md).
methods = {'proj', 'proj_phi_only', 'euler'};
npts = 4;
f = fopen('ratmap_v1_1.csv', 'w');
fprintf(f, 'method,whisker,base_x_mm,base_y_mm,base_z_mm,theta_rad,phi_rad,zeta_rad,a_per_mm,s_mm,x_tip_mm');
for k = 0:npts-1, fprintf(f, ',x%d_mm,y%d_mm,z%d_mm', k, k, k); end
fprintf(f, '\n');
for m = 1:numel(methods)
  [x, y, z, S] = Get_RatMap('', 'Npts', npts, 'TGL_PHI', methods{m});
  for i = 1:size(S.wname, 1)
    % The toolbox draws (xx, -a xx^2) for xx in [0, x_tip]; recover x_tip from the chord base -> tip.
    d2 = (x(i,end) - x(i,1))^2 + (y(i,end) - y(i,1))^2 + (z(i,end) - z(i,1))^2;
    a = S.C_a(i);
    x_tip = sqrt((sqrt(1 + 4 * a^2 * d2) - 1) / (2 * a^2));
    fprintf(f, '%s,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g', methods{m}, S.wname(i,:), ...
            S.C_baseX(i), S.C_baseY(i), S.C_baseZ(i), S.C_theta(i), S.C_phi(i), S.C_zeta(i), a, S.C_s(i), x_tip);
    for k = 1:npts, fprintf(f, ',%.17g,%.17g,%.17g', x(i,k), y(i,k), z(i,k)); end
    fprintf(f, '\n');
  end
end
fclose(f);

% The projection methods' quadrant branches: the same whiskers with the projection theta set to other values
% ('W_th'), so that every branch of the phi conversion is taken (psi-based branches included).
f = fopen('ratmap_v1_1_phi_branches.csv', 'w');
fprintf(f, 'method,whisker,theta_projection_deg,theta_rad,phi_rad\n');
for m = 1:2
  for th = [5 30 60 80 95 120 150 175]
    [x, y, z, S] = Get_RatMap('', 'Npts', 2, 'TGL_PHI', methods{m}, 'W_th', th);
    for i = 1:size(S.wname, 1)
      fprintf(f, '%s,%s,%.17g,%.17g,%.17g\n', methods{m}, S.wname(i,:), th, S.C_theta(i), S.C_phi(i));
    end
  end
end
fclose(f);
