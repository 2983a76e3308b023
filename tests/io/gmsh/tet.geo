// The bar of block.geo (1 x 0.4 x 0.2 m) meshed freely in 10-node tetrahedra of about 0.15 m
SetFactory("Built-in");
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 0.4, 0}; Point(4) = {0, 0.4, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Mesh.MeshSizeMin = 0.15; Mesh.MeshSizeMax = 0.15;
out[] = Extrude {0, 0, 0.2} { Surface{1}; };
Physical Volume("bar") = {out[1]};
Physical Surface("root") = {out[5]};
Mesh.ElementOrder = 2;
