// A 1 x 0.4 x 0.2 m steel bar, 6 x 2 x 2 hexahedra of 20 nodes, clamped at x = 0
SetFactory("Built-in");
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 0.4, 0}; Point(4) = {0, 0.4, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 7; Transfinite Curve{2, 4} = 3;
Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude {0, 0, 0.2} { Surface{1}; Layers{2}; Recombine; };
Physical Volume("bar") = {out[1]};
Physical Surface("root") = {out[5]};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
