#version 3.7;
global_settings { radiosity { count 100 error_bound 0.5 } max_trace_level 6 }
camera { location <0, 1, -3> look_at <0, 0, 0> }
light_source { <2, 3, -4> color rgb 1 }
sphere { 0, 1 pigment { color rgb <1, 0.5, 0.2> } finish { emission 0.8 diffuse 0.2 } }
plane { y, -1 pigment { color rgb 0.7 } }
