// cylinder.geo - quarter of a thick-walled cylinder slab for the inflation (Lame) benchmark.
// Units: metres. Gmsh 4.8, OpenCASCADE kernel. Inner radius A, outer radius B, axial height t,
// the quarter x >= 0, y >= 0, z = 0..t.
//
// Physical groups
//   volume:   solid
//   surfaces: inner (r = A, pressure), outer (r = B), sym_x (plane x = 0: fix u_x),
//             sym_y (plane y = 0: fix u_y), bottom (z = 0), top (z = t) -- fix u_z on both for
//             plane strain.
// Mesh size h (uniform). Every number is a parameter: define it before including this file.

SetFactory("OpenCASCADE");

If(!Exists(A)) A = 6.0e-3; EndIf
If(!Exists(B)) B = 8.5e-3; EndIf
If(!Exists(t)) t = 1.0e-3; EndIf
If(!Exists(h)) h = 0.5e-3; EndIf

eps = 1e-3 * Min(t, B - A); // above the ~1e-7 padding of OCC bounding boxes
Cylinder(1) = {0, 0, 0, 0, 0, t, B, Pi / 2};
Cylinder(2) = {0, 0, -t, 0, 0, 3 * t, A, Pi / 2};
v() = BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; };
Physical Volume("solid") = {v()};

inner() = {}; outer() = {}; sx() = {}; sy() = {}; bot() = {}; top() = {};
bnd() = Boundary{ Volume{v()}; };
For i In {0 : #bnd() - 1}
  s = Abs(bnd(i));
  bb() = BoundingBox Surface{s};
  If(bb(3) < eps)
    sx() += s;
  ElseIf(bb(4) < eps)
    sy() += s;
  ElseIf(bb(5) < eps)
    bot() += s;
  ElseIf(bb(2) > t - eps)
    top() += s;
  ElseIf(bb(3) < A + eps && bb(4) < A + eps)
    inner() += s;
  Else
    outer() += s;
  EndIf
EndFor
Physical Surface("inner") = {inner()};
Physical Surface("outer") = {outer()};
Physical Surface("sym_x") = {sx()};
Physical Surface("sym_y") = {sy()};
Physical Surface("bottom") = {bot()};
Physical Surface("top") = {top()};

Mesh.MeshSizeMax = h;
Mesh.MeshSizeMin = 0;
Mesh.MeshSizeFromCurvature = 0;
