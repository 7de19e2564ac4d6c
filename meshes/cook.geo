// cook.geo - Cook's membrane as a 3-D slab, for the locking benchmark.
// Units: metres (the classical panel is 48 x 44/16 with corners (0,0), (48,44), (48,60), (0,44)
// in units of `scale`; scale = 1e-3 gives mm, scale = 1 the dimensionless benchmark).
// Gmsh 4.8, OpenCASCADE kernel. Thickness t (z = 0..t).
//
// Physical groups
//   volume:   solid
//   surfaces: clamped (x = 0), loaded (x = 48 scale, the right edge face: shear load),
//             front (z = t), back (z = 0) -- fix u_z on both for plane strain --,
//             free (the two slanted edge faces).
// Mesh size h (uniform). Every number is a parameter: define it before including this file.

SetFactory("OpenCASCADE");

If(!Exists(scale)) scale = 1.0e-3; EndIf
If(!Exists(t)) t = 1.0 * scale; EndIf
If(!Exists(h)) h = 4.0 * scale; EndIf

eps = 1e-3 * Min(t, 16 * scale); // above the ~1e-7 padding of OCC bounding boxes
Point(1) = {0, 0, 0};
Point(2) = {48 * scale, 44 * scale, 0};
Point(3) = {48 * scale, 60 * scale, 0};
Point(4) = {0, 44 * scale, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
ext() = Extrude {0, 0, t} { Surface{1}; };
v = ext(1);
Physical Volume("solid") = {v};

cl() = {}; ld() = {}; fr() = {}; bk() = {}; fre() = {};
bnd() = Boundary{ Volume{v}; };
For i In {0 : #bnd() - 1}
  s = Abs(bnd(i));
  bb() = BoundingBox Surface{s};
  If(bb(3) < eps)
    cl() += s;
  ElseIf(bb(0) > 48 * scale - eps)
    ld() += s;
  ElseIf(bb(5) < eps)
    bk() += s;
  ElseIf(bb(2) > t - eps)
    fr() += s;
  Else
    fre() += s;
  EndIf
EndFor
Physical Surface("clamped") = {cl()};
Physical Surface("loaded") = {ld()};
Physical Surface("front") = {fr()};
Physical Surface("back") = {bk()};
Physical Surface("free") = {fre()};

Mesh.MeshSizeMax = h;
Mesh.MeshSizeMin = 0;
Mesh.MeshSizeFromCurvature = 0;
