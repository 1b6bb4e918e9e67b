% whiskers100.json: the rest nodes of the N = 100 side-by-side whiskers (docs/performance.md).
names = {'planar100','spatial100'}; out = 'whiskers100.json';
write_nodes
