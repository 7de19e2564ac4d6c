// fill.geo - the Mohr-Coulomb fill of the granular actuator's continuum scene
// (cases/granular_bending_mc.ini, docs/mohr_coulomb.md "The actuator scene"): a solid cylinder
// filling the bore (cavity of the silicone + rigid feed barrel, /work/shared/ACTUATOR.md) from the
// cavity floor z_floor to the bed surface z_top. Its own body: it shares no nodes with the
// silicone (meshes/actuator.geo) and touches it only through contact. Units: metres.
// Gmsh 4.8, OpenCASCADE kernel. Split at z = 0 (the top of the silicone, where the rigid
// barrel begins) so the lateral surface below and above are separate groups.
//
// Physical groups
//   volumes:  fill
//   surfaces: fill_cavity (lateral surface for z <= 0 and the bottom face: against the cavity
//                          wall and floor of the silicone),
//             fill_barrel (lateral surface for z >= 0: against the rigid barrel),
//             fill_top    (the bed surface z = z_top: the piston face)
// Mesh size: h everywhere (the scene's [mc_bending] fill_h).

SetFactory("OpenCASCADE");

If(!Exists(R_bore)) R_bore = 6.0e-3; EndIf
If(!Exists(z_floor)) z_floor = -80.0e-3; EndIf
If(!Exists(z_top)) z_top = 30.0e-3; EndIf
If(!Exists(h)) h = 4.0e-3; EndIf

eps = 1e-6;
Cylinder(1) = {0, 0, z_floor, 0, 0, -z_floor, R_bore};
Cylinder(2) = {0, 0, 0, 0, 0, z_top, R_bore};
v() = BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; };
Physical Volume("fill") = {Volume{:}};

bnd() = CombinedBoundary{ Volume{:}; };
cav() = {}; bar() = {}; top() = {};
For i In {0 : #bnd() - 1}
  s = Abs(bnd(i));
  bb() = BoundingBox Surface{s};
  If(bb(2) > z_top - eps)
    top() += s;
  ElseIf(bb(5) < eps)
    cav() += s;
  Else
    bar() += s;
  EndIf
EndFor
Physical Surface("fill_cavity") = {cav()};
Physical Surface("fill_barrel") = {bar()};
Physical Surface("fill_top") = {top()};

Mesh.CharacteristicLengthMin = 0.5 * h;
Mesh.CharacteristicLengthMax = h;
