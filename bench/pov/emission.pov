// finish { emission }: POV-Ray adds the pigment's colour times it to every point of the surface,
// whatever lights it (strahl: material.emission, docs/pov-import.md). bench/povray-import.sh
// renders it in POV-Ray and in strahl; the images agree to an RMSE of about 4e-6.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0, 1, -3> look_at <0, 0.3, 0> right x*16/9 }
light_source { <2, 3, -4> color rgb 1 }
sphere { <-0.6, 0.5, 0>, 0.5 pigment { color rgb <1, 0.5, 0.2> } finish { ambient 0 diffuse 0.6 emission 0.5 } }
sphere { <0.6, 0.4, 0.2>, 0.4 pigment { color rgb <0.3, 0.6, 1> } finish { ambient 0.1 diffuse 0.5 emission rgb <0.2, 0.5, 1> } }
plane { y, 0 pigment { color rgb 0.7 } finish { ambient 0.1 diffuse 0.6 } }
