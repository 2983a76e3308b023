// A 2 x 1 m plate, 4 x 2 quadrilaterals of second order (8-node serendipity)
Point(1) = {0, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 5; Transfinite Curve{2, 4} = 3;
Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("plate") = {1};
Physical Curve("root") = {4};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
