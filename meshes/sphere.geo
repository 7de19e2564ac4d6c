// sphere.geo - octant of a thick-walled sphere for the limit-point inflation benchmark.
// Units: metres. Gmsh 4.8, OpenCASCADE kernel. Inner radius A, outer radius B, the octant
// x, y, z >= 0.
//
// Physical groups
//   volume:   solid
//   surfaces: inner (r = A, pressure), outer (r = B), sym_x (plane x = 0: fix u_x),
//             sym_y (plane y = 0), sym_z (plane z = 0).
// Mesh size h (uniform). Every number is a parameter: define it before including this file.

SetFactory("OpenCASCADE");

If(!Exists(A)) A = 10.0e-3; EndIf
If(!Exists(B)) B = 12.5e-3; EndIf
If(!Exists(h)) h = 1.0e-3; EndIf

eps = 1e-3 * (B - A); // above the ~1e-7 padding of OCC bounding boxes
Sphere(1) = {0, 0, 0, B};
Sphere(2) = {0, 0, 0, A};
shell() = BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(3) = {0, 0, 0, 2 * B, 2 * B, 2 * B};
v() = BooleanIntersection{ Volume{shell()}; Delete; }{ Volume{3}; Delete; };
Physical Volume("solid") = {v()};

inner() = {}; outer() = {}; sx() = {}; sy() = {}; sz() = {};
bnd() = Boundary{ Volume{v()}; };
For i In {0 : #bnd() - 1}
  s = Abs(bnd(i));
  bb() = BoundingBox Surface{s};
  If(bb(3) < eps)
    sx() += s;
  ElseIf(bb(4) < eps)
    sy() += s;
  ElseIf(bb(5) < eps)
    sz() += s;
  ElseIf(bb(3) < A + eps && bb(4) < A + eps && bb(5) < A + eps)
    inner() += s;
  Else
    outer() += s;
  EndIf
EndFor
Physical Surface("inner") = {inner()};
Physical Surface("outer") = {outer()};
Physical Surface("sym_x") = {sx()};
Physical Surface("sym_y") = {sy()};
Physical Surface("sym_z") = {sz()};

Mesh.MeshSizeMax = h;
Mesh.MeshSizeMin = 0;
Mesh.MeshSizeFromCurvature = 0;
