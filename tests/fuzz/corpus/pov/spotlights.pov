// Spotlights for POV-Ray 3.7 and strahl's importer (bench/povray-import.sh): three coloured spots with
// tightness, a hard-ish edge and a wide one, one with POV-Ray's defaults (radius 30, falloff 45)
// that fades with distance, and a fading point light.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 8 ambient_light rgb 1 }
camera { perspective location <0, 3.2, -7.5> look_at <0, 0.6, 0> right x*image_width/image_height angle 50 }
#declare F = finish { ambient 0.1 diffuse 0.7 specular 0.5 roughness 0.0125 }
light_source { <-5, 6, -2> color rgb <1.2, 0.42, 0.36> spotlight point_at <-1, 0, 0> radius 12 falloff 20 tightness 10 }
light_source { <5, 6, -2> color rgb <0.36, 0.54, 1.2> spotlight point_at <1, 0, 0> radius 12 falloff 20 tightness 10 }
light_source { <0, 7, 3> color rgb <1, 0.95, 0.6> spotlight point_at <0, 0, -0.8> radius 8 falloff 25 }
light_source { <0.5, 6, -1> color rgb 1 spotlight point_at <0, 0, 0> fade_distance 5 fade_power 1.5 }
light_source { <-3, 2, -4> color rgb <0.3, 0.3, 0.2> fade_distance 2 fade_power 2 }
plane { y, 0 pigment { color rgb 0.8 } finish { ambient 0.1 diffuse 0.8 } }
sphere { <-1.4, 0.8, 0>, 0.8 pigment { color rgb 0.9 } finish { F } }
sphere { <1.4, 0.8, 0>, 0.8 pigment { color rgb 0.9 } finish { F } }
sphere { <0, 0.6, -1.3>, 0.6 pigment { color rgb <0.2, 0.6, 0.3> } finish { F } }
