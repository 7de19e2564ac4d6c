// actuator.geo - the reference granular-driven bending actuator of /work/shared/ACTUATOR.md
// (docs: meshes/README.md). Units: metres. Gmsh 4.8, OpenCASCADE kernel.
//
// Silicone hollow cylinder (cavity radius R_cav, outer radius R_out, cavity length L_cav, tip cap
// t_cap; top face at z = 0, tip at z = -(L_cav + t_cap)), an embedded strain-limiting band (radii
// band_r_in..band_r_out, arc band_w at its mid radius, centred on -x, z = -L_cav..0) and, if
// rings = 1, ring_n reinforcement rings flush with the outside (radii R_out - ring_d .. R_out,
// height ring_h, centred at z = ring_z0 - k ring_pitch). All parts are fragmented together so the
// regions share nodes (conforming mesh).
//
// Physical groups
//   volumes:  silicone, strain_limit, reinforcement (only if rings = 1)
//   surfaces: cavity_wall (cavity side wall + floor: the pressure surface),
//             fixed_end   (outer surface for z >= -L_fix and the top annulus z = 0),
//             tip         (outer face of the cap, z = -(L_cav + t_cap)),
//             outer       (the rest of the outside)
//
// Mesh size: h everywhere, h_band in the 0.5 mm band and h_ring in the rings (growing back to h over
// a distance thin_grow), so the thin parts get enough elements without refining the wall. The
// 0.5 mm faces of the rings and band force about 0.5 mm elements there whatever h_ring is; h_ring
// <= 4 ring_h keeps the sagitta of a curved tet10 edge on the outer surface, c^2 / (8 R_out),
// at a tenth of the ring height (coarser rings gave tet10 elements with det J < 0 at h = 3 mm).
// h_corner > 0 (default 0: off) grades the size toward the corners of the ring sections.
// Every number below is a parameter: define it before including this file to override.

SetFactory("OpenCASCADE");

If(!Exists(R_cav)) R_cav = 6.0e-3; EndIf
If(!Exists(R_out)) R_out = 8.5e-3; EndIf
If(!Exists(L_cav)) L_cav = 80.0e-3; EndIf
If(!Exists(t_cap)) t_cap = 4.0e-3; EndIf
If(!Exists(L_fix)) L_fix = 5.0e-3; EndIf
If(!Exists(band_r_in)) band_r_in = 7.0e-3; EndIf
If(!Exists(band_r_out)) band_r_out = 7.5e-3; EndIf
If(!Exists(band_w)) band_w = 10.0e-3; EndIf
If(!Exists(rings)) rings = 1; EndIf
If(!Exists(ring_n)) ring_n = 16; EndIf
If(!Exists(ring_d)) ring_d = 0.5e-3; EndIf
If(!Exists(ring_h)) ring_h = 0.5e-3; EndIf
If(!Exists(ring_pitch)) ring_pitch = 5.0e-3; EndIf
If(!Exists(ring_z0)) ring_z0 = -2.5e-3; EndIf
If(!Exists(h)) h = 2.0e-3; EndIf
If(!Exists(h_band)) h_band = Min(h, 2 * (band_r_out - band_r_in)); EndIf
If(!Exists(h_ring)) h_ring = Min(h, 4 * ring_h); EndIf
If(!Exists(thin_grow)) thin_grow = h; EndIf
If(!Exists(h_corner)) h_corner = 0; EndIf
If(!Exists(corner_grade)) corner_grade = 0.5; EndIf

eps = 1e-3 * ring_h; // bounding-box tolerance, far below every feature size
L_tot = L_cav + t_cap;

// Body, split at z = -L_fix so the clamped band of the outer surface is its own face.
Cylinder(1) = {0, 0, -L_fix, 0, 0, L_fix, R_out};
Cylinder(2) = {0, 0, -L_tot, 0, 0, L_tot - L_fix, R_out};
// The cavity tool overshoots the top face so no coincident faces are left to the boolean.
Cylinder(3) = {0, 0, -L_cav, 0, 0, L_cav + 1e-3, R_cav};
body() = BooleanDifference{ Volume{1, 2}; Delete; }{ Volume{3}; Delete; };

// Strain-limiting band: annular sector of half-angle a about -x.
a = 0.5 * band_w / (0.5 * (band_r_in + band_r_out));
Cylinder(4) = {0, 0, -L_cav, 0, 0, L_cav, band_r_out, 2 * a};
Cylinder(5) = {0, 0, -L_cav - 1e-3, 0, 0, L_cav + 2e-3, band_r_in, 2 * a};
band() = BooleanDifference{ Volume{4}; Delete; }{ Volume{5}; Delete; };
Rotate {{0, 0, 1}, {0, 0, 0}, Pi - a} { Volume{band()}; }

tools() = band();
If(rings)
  For k In {0 : ring_n - 1}
    zc = ring_z0 - k * ring_pitch;
    ro = newv; Cylinder(ro) = {0, 0, zc - 0.5 * ring_h, 0, 0, ring_h, R_out};
    ri = newv; Cylinder(ri) = {0, 0, zc - 0.5 * ring_h - 1e-3, 0, 0, ring_h + 2e-3, R_out - ring_d};
    r() = BooleanDifference{ Volume{ro}; Delete; }{ Volume{ri}; Delete; };
    tools() += r();
  EndFor
EndIf

all() = BooleanFragments{ Volume{body()}; Delete; }{ Volume{tools()}; Delete; };

// Classify the fragments by bounding box: band pieces lie in x < 0, each ring in its own slab.
band_v() = Volume In BoundingBox{-R_out - eps, -R_out - eps, -L_cav - eps, 0, R_out + eps, eps};
ring_v() = {};
If(rings)
  For k In {0 : ring_n - 1}
    zc = ring_z0 - k * ring_pitch;
    ring_v() += Volume In BoundingBox{-R_out - eps, -R_out - eps, zc - 0.5 * ring_h - eps,
                                      R_out + eps, R_out + eps, zc + 0.5 * ring_h + eps};
  EndFor
EndIf
sil_v() = Volume{:};
sil_v() -= band_v();
sil_v() -= ring_v();

Physical Volume("silicone") = {sil_v()};
Physical Volume("strain_limit") = {band_v()};
If(rings)
  Physical Volume("reinforcement") = {ring_v()};
EndIf

// Outside surfaces: the boundary of the union (interfaces between regions cancel).
bnd() = CombinedBoundary{ Volume{:}; };
cav() = {}; fix() = {}; tipf() = {}; out() = {};
For i In {0 : #bnd() - 1}
  s = Abs(bnd(i));
  bb() = BoundingBox Surface{s};
  If(bb(0) > -R_cav - eps && bb(3) < R_cav + eps && bb(1) > -R_cav - eps && bb(4) < R_cav + eps)
    cav() += s;
  ElseIf(bb(2) > -L_fix - eps)
    fix() += s;
  ElseIf(bb(5) < -L_tot + eps)
    tipf() += s;
  Else
    out() += s;
  EndIf
EndFor
Physical Surface("cavity_wall") = {cav()};
Physical Surface("fixed_end") = {fix()};
Physical Surface("tip") = {tipf()};
Physical Surface("outer") = {out()};

// Mesh size: h, refined to h_band in the band and h_ring in the rings, growing linearly back to h
// over thin_grow. An analytic gap function (MathEval) replaces a Distance field, which would need
// millions of sample points to resolve 80 mm long, 0.5 mm thick parts.
//   band gap:  radial |r - r_mid| - t/2, lateral Max(|y| - r sin a, x + r cos a) (zero inside the
//              sector about -x, an under-estimate of the arc distance outside), axial outside
//              -L_cav..0;
//   ring gap:  axial |z - z_k| - ring_h/2 to the nearest ring, radial (R_out - ring_d) - r.
r_mid = 0.5 * (band_r_in + band_r_out);
band_t = band_r_out - band_r_in;
R = "Sqrt(x*x+y*y)";
gb = StrCat("Max(Max(Fabs(", R, Sprintf("-%.9g)-%.9g", r_mid, 0.5 * band_t),
            ", Max(Fabs(y)-", R, Sprintf("*%.9g", Sin(a)), ", x+", R, Sprintf("*%.9g", Cos(a)),
            Sprintf(")), Max(-%.9g-z, z))", L_cav));
F = StrCat(Sprintf("Min(%.9g, %.9g + %.9g*Max(0, ", h, h_band, (h - h_band) / thin_grow), gb, "))");
If(rings)
  // nearest ring index, clamped to 0..ring_n-1
  kr = Sprintf("Max(0, Min(%.9g, Floor((%.9g-z)/%.9g+0.5)))", ring_n - 1, ring_z0, ring_pitch);
  gr = StrCat(Sprintf("Max(Fabs(z-(%.9g-%.9g*", ring_z0, ring_pitch), kr,
              Sprintf("))-%.9g, %.9g-", 0.5 * ring_h, R_out - ring_d), R, ")");
  F = StrCat("Min(", F, Sprintf(", %.9g + %.9g*Max(0, ", h_ring, (h - h_ring) / thin_grow), gr, "))");
  // h_corner > 0: grading toward the four corner circles of each ring section, where the
  // bonded stiff ring makes the stresses singular (docs/fem_time_to_accuracy.md): the size is
  // h_corner + corner_grade * (distance to the nearest corner), capped by the sizes above.
  If(h_corner > 0)
    dzc = StrCat("(Fabs(z-(", Sprintf("%.9g-%.9g*", ring_z0, ring_pitch), kr, Sprintf("))-%.9g)", 0.5 * ring_h));
    d_in = StrCat("Sqrt((", R, Sprintf("-%.9g)^2+", R_out - ring_d), dzc, "^2)");
    d_out = StrCat("Sqrt((", R, Sprintf("-%.9g)^2+", R_out), dzc, "^2)");
    F = StrCat("Min(", F, Sprintf(", %.9g + %.9g*Min(", h_corner, corner_grade), d_in, ",", d_out, "))");
  EndIf
EndIf
Field[1] = MathEval;
Field[1].F = StrCat(F, "");
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeMax = h;
