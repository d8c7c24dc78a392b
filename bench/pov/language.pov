// POV-Ray's language as strahl reads it (docs/pov-import.md): directives, expressions, a
// left-handed camera, CSG with an inverse, a glass union, a checker plane (bench/povray-import.sh).
#version 3.7;
#declare R = 0.5;
#declare T = texture { pigment { color rgbf <0.7, 0.7, 1, 0.9> } finish { specular 0.6 roughness 0.01 reflection { 0.1 } } }
camera { location <0, 1, -3> look_at <0, 0.5, 0> angle 60 }
light_source { <2, 4, -3> color rgb 1 }
global_settings { max_trace_level 6 ambient_light rgb <1, 1, 1> }
background { color rgb <0.1, 0.2, 0.3> }
#for (I, 0, 2)
  sphere { <I - 1, R, 0>, R pigment { color rgb <1, I / 2, 0> } finish { specular 0.5 roughness 0.02 } }
#end
#declare J = 0;
#while (J < 2)
  #if (J = 0) box { <-2, 0, 1>, <-1.5, 0.5, 1.5> } #else cylinder { <2, 0, 1>, <2, 1, 1>, 0.25 open } #end
  #declare J = J + 1;
#end
union { sphere { <0, 1.5, 0>, 0.3 } torus { 0.4, 0.1 rotate <90, 0, 0> } translate <0, 0.5, 1> texture { T } interior { ior 1.5 } }
difference { box { -0.3, 0.3 } sphere { 0, 0.4 inverse } translate <1.5, 0.3, -1> pigment { color rgb <vlength(<3, 4, 0>) / 5, 0, 0> } }
plane { y, 0 pigment { checker color rgb 1, color rgb 0.1 scale 0.5 } }
