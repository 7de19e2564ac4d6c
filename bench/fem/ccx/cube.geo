// cube.geo - verification block for the CalculiX exporter (bench/fem/ccx/run.sh verify): a box
// [0,Lx] x [0,Ly] x [0,Lz] with every face its own physical group, so rollers on x0, y0, z0 and a
// pressure on top give homogeneous uniaxial stress (exact answer: ccx_post uniaxial).
SetFactory("OpenCASCADE");
If(!Exists(Lx)) Lx = 10e-3; EndIf
If(!Exists(Ly)) Ly = 10e-3; EndIf
If(!Exists(Lz)) Lz = 10e-3; EndIf
If(!Exists(h)) h = 4e-3; EndIf
Box(1) = {0, 0, 0, Lx, Ly, Lz};
// OpenCASCADE numbers a box's faces x = 0, x = Lx, y = 0, y = Ly, z = 0, z = Lz as 1..6.
Physical Volume("silicone") = {1};
Physical Surface("x0") = {1};
Physical Surface("y0") = {3};
Physical Surface("z0") = {5};
Physical Surface("top") = {6};
Physical Surface("sides") = {2, 4};
Mesh.MeshSizeMax = h;
