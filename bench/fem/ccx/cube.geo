// cube.geo - verification block for the CalculiX exporter (bench/fem/ccx/verify.sh): a box
// [0,Lx] x [0,Ly] x [0,Lz] with every face its own physical group, so rollers on x0, y0, z0 and a
// pressure on top give homogeneous uniaxial stress (exact answer: ccx_post uniaxial).
SetFactory("OpenCASCADE");
If(!Exists(Lx)) Lx = 10e-3; EndIf
If(!Exists(Ly)) Ly = 10e-3; EndIf
If(!Exists(Lz)) Lz = 10e-3; EndIf
If(!Exists(h)) h = 4e-3; EndIf
Box(1) = {0, 0, 0, Lx, Ly, Lz};
e = 1e-6 * Lx;
Physical Volume("silicone") = {1};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, Ly + e, Lz + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, Lx + e, e, Lz + e};
Physical Surface("z0") = Surface In BoundingBox{-e, -e, -e, Lx + e, Ly + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, Lz - e, Lx + e, Ly + e, Lz + e};
Physical Surface("sides") = Surface In BoundingBox{Lx - e, -e, -e, Lx + e, Ly + e, Lz + e};
Physical Surface("sides") += Surface In BoundingBox{-e, Ly - e, -e, Lx + e, Ly + e, Lz + e};
Mesh.MeshSizeMax = h;
