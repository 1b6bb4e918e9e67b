function [X, I] = whiskers(name)
% Rest nodes (3 x n, world frame) and per-node area moments used for the vibrissa fixtures.
switch name
  case 'planar30'   % y = 20 x^2, arc length 30 mm, 30 equal links
    L = 0.030; a = 20; n = 31;
    xd = linspace(0, 0.031, 20001); yd = a*xd.^2;
    sd = [0 cumsum(sqrt(diff(xd).^2 + diff(yd).^2))];
    s = linspace(0, L, n);
    X = [interp1(sd, xd, s); interp1(sd, yd, s); zeros(1, n)];
  case 'spatial40'  % 3D curve, unequal links, rotated and translated
    n = 41; U = 0.028; v = (0:n-1)/(n-1);
    u = U*(0.7*v + 0.3*v.^2);
    P = [u; 15*u.^2; 40*u.^3];
    c = cos(0.4); s = sin(0.4); Rz = [c -s 0; s c 0; 0 0 1];
    c = cos(-0.3); s = sin(-0.3); Ry = [c 0 s; 0 1 0; -s 0 c];
    c = cos(0.7); s = sin(0.7); Rx = [1 0 0; 0 c -s; 0 s c];
    X = Rz*Ry*Rx*P + [1e-3; -2e-3; 0.5e-3];
  case 'planar100'  % the same parabola in 100 equal links (side by side, docs/performance.md)
    L = 0.030; a = 20; n = 101;
    xd = linspace(0, 0.031, 20001); yd = a*xd.^2;
    sd = [0 cumsum(sqrt(diff(xd).^2 + diff(yd).^2))];
    s = linspace(0, L, n);
    X = [interp1(sd, xd, s); interp1(sd, yd, s); zeros(1, n)];
  case 'spatial100' % the same 3D curve in 100 unequal links
    n = 101; U = 0.028; v = (0:n-1)/(n-1);
    u = U*(0.7*v + 0.3*v.^2);
    P = [u; 15*u.^2; 40*u.^3];
    c = cos(0.4); s = sin(0.4); Rz = [c -s 0; s c 0; 0 0 1];
    c = cos(-0.3); s = sin(-0.3); Ry = [c 0 s; 0 1 0; -s 0 c];
    c = cos(0.7); s = sin(0.7); Rx = [1 0 0; 0 c -s; 0 s c];
    X = Rz*Ry*Rx*P + [1e-3; -2e-3; 0.5e-3];
end
sn = [0 cumsum(sqrt(sum(diff(X,1,2).^2,1)))];
r = 100e-6*(1 - (1 - 1/15)*sn/sn(end));   % vibrissa's default: radius linear in arc length
I = (pi/4)*r.^4;
end
