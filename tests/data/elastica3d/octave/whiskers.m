function [X, I] = whiskers(name)
% Rest nodes (3 x n, world frame) and per-node area moments used for the vibrissa fixtures.
switch name
  case {'planar30', 'planar100'}   % y = 20 x^2, arc length 30 mm, 30 (100: side by side) equal links
    L = 0.030; a = 20; n = 1 + str2double(name(7:end));
    xd = linspace(0, 0.031, 20001); yd = a*xd.^2;
    sd = [0 cumsum(sqrt(diff(xd).^2 + diff(yd).^2))];
    s = linspace(0, L, n);
    X = [interp1(sd, xd, s); interp1(sd, yd, s); zeros(1, n)];
  case {'spatial40', 'spatial100'}  % 3D curve, 40 (100: side by side) unequal links, rotated and translated
    n = 1 + str2double(name(8:end)); U = 0.028; v = (0:n-1)/(n-1);
    u = U*(0.7*v + 0.3*v.^2);
    P = [u; 15*u.^2; 40*u.^3];
    c = cos(0.4); s = sin(0.4); Rz = [c -s 0; s c 0; 0 0 1];
    c = cos(-0.3); s = sin(-0.3); Ry = [c 0 s; 0 1 0; -s 0 c];
    c = cos(0.7); s = sin(0.7); Rx = [1 0 0; 0 c -s; 0 s c];
    X = Rz*Ry*Rx*P + [1e-3; -2e-3; 0.5e-3];
  otherwise
    error('whiskers: unknown whisker %s', name);
end
sn = [0 cumsum(sqrt(sum(diff(X,1,2).^2,1)))];
r = 100e-6*(1 - (1 - 1/15)*sn/sn(end));   % vibrissa's default: radius linear in arc length
I = (pi/4)*r.^4;
end
